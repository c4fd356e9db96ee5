// The scene's materials as both GPU integrators read them (engine/gputrace's
// GpuMaterial, std430): a MaterialDesc's own weights, as RtScene::materialAt gives
// them where no texture is.

struct RtMaterial {
  vec4 colorAmbient;                         // colour, ambient
  vec4 diffuseSpecularShininessReflection;
  vec4 metallicRoughnessUnlit;               // metallic, roughness, unlit (0 or 1)
  vec4 emission;
  vec4 dielectric;                           // f0 (KHR_materials_ior, _specular), f90
};

layout(std430, binding = BUFFER_RT_MATERIALS) readonly buffer RtMaterials { RtMaterial rtMaterials[]; };
