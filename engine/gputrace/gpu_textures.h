#pragma once
// The textures the CPU tracer samples (raytrace/texture.h's RtTexture: every mipmap
// level in linear RGBA, the wrap modes, the uv set and the KHR_texture_transform
// matrix) and the terrains' layered materials, flattened for the GPU tracer, whose
// shaders/rt/texture.glsl samples them as RtTexture::sampleRgba does, operation for
// operation: one array of every texel, and a record per texture (std430, rt/texture.glsl's
// RtTexture). GL-free.
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/rt_scene.h"

namespace engine::rt {

// Mipmap levels a GPU texture record holds: up to 32768 texels a side.
inline constexpr int kGpuTextureLevels = 16;

struct GpuTexture {
  glm::ivec4 info;         // levels, wrap s, wrap t (GL's enums, as TextureWrap), uv set
  glm::vec4 transform[3];  // the uv transform's columns; [0].w its footprint scale, [1].w 1 when not the identity
  glm::ivec4 level[kGpuTextureLevels];  // first texel, width, height
};
static_assert(sizeof(GpuTexture) == 320);

// Where a terrain's three layer images are in the set, and its constants: what its
// material's record carries (gputrace/gpu_materials.h), not uploaded as it is.
struct GpuTerrain {
  glm::ivec4 layers;  // grass, rock, snow: GpuTextureSet::textures indices
  glm::dvec2 originYHeightScale;  // the terrain origin's world height; the height scale
};

struct GpuTextureSet {
  // RtScene::textures() in their order (MaterialExtras' indices stay valid), then
  // each terrain's grass, rock and snow.
  std::vector<GpuTexture> textures;
  std::vector<glm::vec4> texels;
  std::vector<GpuTerrain> terrains;  // RtScene::terrains() order
};

// Whether every texture fits a record (kGpuTextureLevels levels).
bool fitsGpuTextures(const RtScene& scene);
GpuTextureSet flattenTextures(const RtScene& scene);

}  // namespace engine::rt
