// The scene's materials as both GPU integrators read them (engine/gputrace's
// GpuMaterial, std430): a MaterialDesc's own weights, as RtScene::baseMaterial gives
// them, and what RtScene::materialAt changes at a hit (rt/material_at.glsl).

struct RtMaterial {
  vec4 colorAmbient;                         // colour, ambient
  vec4 diffuseSpecularShininessReflection;
  vec4 metallicRoughnessUnlit;               // metallic, roughness, unlit (0 or 1)
  vec4 emission;
  vec4 dielectric;                           // f0 (KHR_materials_ior, _specular), f90
  ivec4 textures;                            // base colour, metallic-roughness, emissive (rt/texture.glsl's; -1 none), terrain (-1 none)
  vec4 surface;                              // x: texture scale (spheres, planes); y: 1 when a hit's uv is read
  vec4 alpha;                                // x: mode (0 opaque, 1 MASK, 2 BLEND), y: factor, z: cutoff, w: 1 when single-sided
  vec4 coatSheen;                            // clear coat, its roughness; the sheen's roughness; iridescence
  vec4 sheenColorFilmIor;                    // the sheen's colour; the thin film's ior
  vec4 film;                                 // x: the thin film's thickness (nm)
  vec4 transmission;                         // share, ior, thickness (0: a thin wall), attenuation distance
  vec4 attenuation;                          // xyz: the volume's attenuation colour
  vec4 anisotropy;                           // x: strength, y: rotation, zw: direction (rtMaterialAt: xyz the stretch in the world, w strength)
  ivec4 terrainLayers;                       // the terrain's grass, rock, snow (textures.w >= 0)
  dvec2 terrainOriginYHeightScale;           // its origin's world height; its height scale
  ivec4 layerTextures[3];                    // glTF's layer textures, TextureSlot::Specular on (-1 none)
  vec4 specularLayer;                        // KHR_materials_specular's colour and weight
  vec4 filmRange;                            // the thin film's thickness at texel 0 and 1 (nm)
  dvec2 reflectance;                         // x: ((ior - 1) / (ior + 1))^2
};

layout(std430, binding = BUFFER_RT_MATERIALS) readonly buffer RtMaterials { RtMaterial rtMaterials[]; };
