#pragma once
// Every texture unit and buffer binding point a program uses, defined once here
// and handed to every GLSL program as #defines (gl::preprocessShader puts them
// after #version), so that the C++ that binds and the GLSL that samples cannot
// disagree: shaders write `layout(binding = UNIT_BASE_COLOR)`, never a number
// (tests/gl/shader_source_test checks). Units are per program: the terrain's
// and post's reuse the material ones' numbers.
#include <array>
#include <string>

namespace engine::gl::binding {

// Material textures (common/material.glsl).
inline constexpr unsigned kBaseColor = 0;
inline constexpr unsigned kNormal = 1;
inline constexpr unsigned kMetallicRoughness = 2;
inline constexpr unsigned kEmissive = 3;
inline constexpr unsigned kOcclusion = 6;
// glTF's layer textures (KHR_materials_specular, _clearcoat, _transmission, _volume).
inline constexpr unsigned kSpecular = 12;
inline constexpr unsigned kSpecularColor = 13;
inline constexpr unsigned kClearcoat = 14;
inline constexpr unsigned kClearcoatRoughness = 15;
inline constexpr unsigned kTransmission = 16;  // KHR_materials_transmission, _volume
inline constexpr unsigned kThickness = 17;
// The opaque pass's colour, mipmapped, that transmissive surfaces refract
// (scene.frag's TRANSMISSION).
inline constexpr unsigned kTransmissionSource = 18;
inline constexpr unsigned kClearcoatNormal = 19;  // KHR_materials_clearcoat's normal map
inline constexpr unsigned kSheenColor = 20;       // KHR_materials_sheen
inline constexpr unsigned kSheenRoughness = 21;
// The white sheen's directional albedo (core/sheen_table.h), for albedo scaling.
inline constexpr unsigned kSheenAlbedo = 22;
inline constexpr unsigned kAnisotropy = 23;  // KHR_materials_anisotropy's texture
inline constexpr unsigned kIridescence = 24;  // KHR_materials_iridescence's textures
inline constexpr unsigned kIridescenceThickness = 25;
// Read per vertex at a per-vertex index, so buffer textures (gl::Texture::ofBuffer
// says why): a morphing primitive's displacements (common/morph.glsl) and a
// skin's palette (common/skinning.glsl).
inline constexpr unsigned kMorphDeltas = 26;
inline constexpr unsigned kSkinPalette = 27;
// Shadow maps (common/shadows.glsl).
inline constexpr unsigned kSunShadow = 4;
inline constexpr unsigned kPointShadow = 5;
inline constexpr unsigned kSunShadowFar = 7;
// Environment (common/shading.glsl, sky.frag).
inline constexpr unsigned kReflectionProbe = 8;
inline constexpr unsigned kSkyImage = 9;
inline constexpr unsigned kSplitSum = 10;
inline constexpr unsigned kPrefiltered = 11;
// The terrain's programs: height pages, then its material layers from 1.
inline constexpr unsigned kTerrainHeights = 0;
inline constexpr unsigned kTerrainLayers = 1;
// The deferred terrain pass's surface (terrain_deferred.frag), where the heights'
// unit would be: that pass reads no heights.
inline constexpr unsigned kTerrainSurface = 0;
// The deferred characters' surface (scene.frag's SURFACE_IN): the units of the
// morph deltas and the skin palette, which that full-screen pass has no vertex to
// deform with.
inline constexpr unsigned kCharacterSurface = 26;
inline constexpr unsigned kCharacterDistance = 27;
// Post's HDR image and the IBL prefilter's source cube.
inline constexpr unsigned kHdr = 0;
inline constexpr unsigned kIblSource = 0;
inline constexpr unsigned kIblLevelImage = 0;  // an image unit: the level being written
// Storage buffers: the morph weights (common/morph.glsl; read at an index every
// vertex shares). Uniform buffers: the frame block (common/frame.glsl).
inline constexpr unsigned kMorphWeightsBuffer = 2;
// The skin cache's compute (skin.comp): a primitive's vertex buffers in, as
// buffer textures on these units, its deformed vertices out, a storage buffer.
inline constexpr unsigned kSkinPositions = 0;
inline constexpr unsigned kSkinNormals = 1;
inline constexpr unsigned kSkinTangents = 2;
inline constexpr unsigned kSkinJoints = 3;
inline constexpr unsigned kSkinWeights = 4;
inline constexpr unsigned kSkinOutput = 8;
inline constexpr unsigned kFrameBlock = 0;
// GPU culling (render/gpu_cull.h): the hierarchical-Z pyramid's build
// (cull/hiz.comp: the level read, the level written) and the cull (cull/cull.comp:
// the pyramid, the clusters, jobs, commands and counters). It runs inside the
// main view's pass, so its texture units are ones no scene program samples.
inline constexpr unsigned kHiZSource = 28;
inline constexpr unsigned kHiZLevelImage = 1;
inline constexpr unsigned kHiZ = 29;
inline constexpr unsigned kCullClusters = 12;
inline constexpr unsigned kCullJobs = 13;
inline constexpr unsigned kCullCommands = 14;
inline constexpr unsigned kCullCounters = 15;
// The display curve's table (core/srgb_curve.h, common/output.glsl): bound once a
// frame for every program that writes display values, on a unit no other program
// samples.
inline constexpr unsigned kDisplayTable = 30;
// The physically based sky (render/atmosphere_tables.h): its compute passes read the
// transmittance, multiple-scattering and ground-irradiance tables on these units and
// write each table through one image unit; sky.frag reads the sky-view table where
// the sky image's unit would be (its atmosphere variant has no image); the
// surfaces read the aerial-perspective volume on a unit no other program samples.
inline constexpr unsigned kSkyTransmittance = 0;
inline constexpr unsigned kSkyMultiScattering = 1;
inline constexpr unsigned kSkyGroundIrradiance = 2;
inline constexpr unsigned kSkyTableImage = 0;
inline constexpr unsigned kSkyView = 9;
inline constexpr unsigned kAerialPerspective = 31;
// The GPU ray tracer (shaders/rt/): the flattened scene (gputrace/gpu_layout.h),
// its materials and lights, and what a kernel reads and writes.
inline constexpr unsigned kRtNodes = 0;
inline constexpr unsigned kRtLeaves = 1;
inline constexpr unsigned kRtOrder = 2;
inline constexpr unsigned kRtInstances = 3;
inline constexpr unsigned kRtSpheres = 4;
inline constexpr unsigned kRtPlanes = 5;
inline constexpr unsigned kRtTriangles = 6;
inline constexpr unsigned kRtMaterials = 7;
inline constexpr unsigned kRtLights = 8;
inline constexpr unsigned kRtInput = 9;
inline constexpr unsigned kRtOutput = 10;
inline constexpr unsigned kRtEnvironment = 11;  // the path tracer's environment tables
// Declared in the kernels only where the scene has them (a compute shader may have
// 16 storage blocks): triangles' uvs and colours, textures (gputrace/gpu_textures.h),
// an image sky's linear RGB.
inline constexpr unsigned kRtTriangleAttributes = 17;
inline constexpr unsigned kRtTextures = 18;
inline constexpr unsigned kRtTexels = 19;
inline constexpr unsigned kRtSkyImage = 20;
// rt/refit.comp's plan (gputrace/gpu_refit.h).
inline constexpr unsigned kRtRefitPlan = 16;

struct Define {
  const char* name;
  unsigned value;
};
inline constexpr std::array<Define, 75> kDefines{{
    {"UNIT_BASE_COLOR", kBaseColor},
    {"UNIT_NORMAL", kNormal},
    {"UNIT_METALLIC_ROUGHNESS", kMetallicRoughness},
    {"UNIT_EMISSIVE", kEmissive},
    {"UNIT_OCCLUSION", kOcclusion},
    {"UNIT_SPECULAR", kSpecular},
    {"UNIT_SPECULAR_COLOR", kSpecularColor},
    {"UNIT_CLEARCOAT", kClearcoat},
    {"UNIT_CLEARCOAT_ROUGHNESS", kClearcoatRoughness},
    {"UNIT_TRANSMISSION", kTransmission},
    {"UNIT_THICKNESS", kThickness},
    {"UNIT_TRANSMISSION_SOURCE", kTransmissionSource},
    {"UNIT_CLEARCOAT_NORMAL", kClearcoatNormal},
    {"UNIT_SHEEN_COLOR", kSheenColor},
    {"UNIT_SHEEN_ROUGHNESS", kSheenRoughness},
    {"UNIT_SHEEN_ALBEDO", kSheenAlbedo},
    {"UNIT_ANISOTROPY", kAnisotropy},
    {"UNIT_IRIDESCENCE", kIridescence},
    {"UNIT_IRIDESCENCE_THICKNESS", kIridescenceThickness},
    {"UNIT_MORPH_DELTAS", kMorphDeltas},
    {"UNIT_SKIN_PALETTE", kSkinPalette},
    {"UNIT_SUN_SHADOW", kSunShadow},
    {"UNIT_POINT_SHADOW", kPointShadow},
    {"UNIT_SUN_SHADOW_FAR", kSunShadowFar},
    {"UNIT_REFLECTION_PROBE", kReflectionProbe},
    {"UNIT_SKY_IMAGE", kSkyImage},
    {"UNIT_SPLIT_SUM", kSplitSum},
    {"UNIT_PREFILTERED", kPrefiltered},
    {"UNIT_TERRAIN_HEIGHTS", kTerrainHeights},
    {"UNIT_TERRAIN_LAYERS", kTerrainLayers},
    {"UNIT_TERRAIN_SURFACE", kTerrainSurface},
    {"UNIT_CHARACTER_SURFACE", kCharacterSurface},
    {"UNIT_CHARACTER_DISTANCE", kCharacterDistance},
    {"UNIT_HDR", kHdr},
    {"UNIT_IBL_SOURCE", kIblSource},
    {"IMAGE_IBL_LEVEL", kIblLevelImage},
    {"BUFFER_MORPH_WEIGHTS", kMorphWeightsBuffer},
    {"UNIT_SKIN_POSITIONS", kSkinPositions},
    {"UNIT_SKIN_NORMALS", kSkinNormals},
    {"UNIT_SKIN_TANGENTS", kSkinTangents},
    {"UNIT_SKIN_JOINTS", kSkinJoints},
    {"UNIT_SKIN_WEIGHTS", kSkinWeights},
    {"BUFFER_SKIN_OUTPUT", kSkinOutput},
    {"BLOCK_FRAME", kFrameBlock},
    {"UNIT_HIZ_SOURCE", kHiZSource},
    {"IMAGE_HIZ_LEVEL", kHiZLevelImage},
    {"UNIT_HIZ", kHiZ},
    {"UNIT_DISPLAY_TABLE", kDisplayTable},
    {"UNIT_SKY_TRANSMITTANCE", kSkyTransmittance},
    {"UNIT_SKY_MULTI_SCATTERING", kSkyMultiScattering},
    {"UNIT_SKY_GROUND_IRRADIANCE", kSkyGroundIrradiance},
    {"IMAGE_SKY_TABLE", kSkyTableImage},
    {"UNIT_SKY_VIEW", kSkyView},
    {"UNIT_AERIAL_PERSPECTIVE", kAerialPerspective},
    {"BUFFER_CULL_CLUSTERS", kCullClusters},
    {"BUFFER_CULL_JOBS", kCullJobs},
    {"BUFFER_CULL_COMMANDS", kCullCommands},
    {"BUFFER_CULL_COUNTERS", kCullCounters},
    {"BUFFER_RT_NODES", kRtNodes},
    {"BUFFER_RT_LEAVES", kRtLeaves},
    {"BUFFER_RT_ORDER", kRtOrder},
    {"BUFFER_RT_INSTANCES", kRtInstances},
    {"BUFFER_RT_SPHERES", kRtSpheres},
    {"BUFFER_RT_PLANES", kRtPlanes},
    {"BUFFER_RT_TRIANGLES", kRtTriangles},
    {"BUFFER_RT_MATERIALS", kRtMaterials},
    {"BUFFER_RT_LIGHTS", kRtLights},
    {"BUFFER_RT_INPUT", kRtInput},
    {"BUFFER_RT_OUTPUT", kRtOutput},
    {"BUFFER_RT_ENVIRONMENT", kRtEnvironment},
    {"BUFFER_RT_TRIANGLE_ATTRIBUTES", kRtTriangleAttributes},
    {"BUFFER_RT_TEXTURES", kRtTextures},
    {"BUFFER_RT_TEXELS", kRtTexels},
    {"BUFFER_RT_SKY_IMAGE", kRtSkyImage},
    {"BUFFER_RT_REFIT_PLAN", kRtRefitPlan},
}};

}  // namespace engine::gl::binding
