#include "gputrace/gpu_textures.h"

#include <algorithm>

namespace engine::rt {
namespace {

void append(const RtTexture& t, GpuTextureSet& out) {
  GpuTexture& g = out.textures.emplace_back();
  g.info = glm::ivec4(t.levels(), int(t.wrapS()), int(t.wrapT()), t.texCoord());
  const glm::mat3& m = t.uvTransform();
  g.transform[0] = glm::vec4(m[0], t.footprintScale());
  g.transform[1] = glm::vec4(m[1], t.transformed() ? 1.0f : 0.0f);
  g.transform[2] = glm::vec4(m[2], 0.0f);
  for (int level = 0; level < t.levels() && level < kGpuTextureLevels; ++level) {
    const glm::ivec2 size = t.levelSize(level);
    g.level[level] = glm::ivec4(int(out.texels.size()), size.x, size.y, 0);
    const std::vector<glm::vec4>& texels = t.levelTexels(level);
    out.texels.insert(out.texels.end(), texels.begin(), texels.end());
  }
}

}  // namespace

bool fitsGpuTextures(const RtScene& scene) {
  const auto fits = [](const RtTexture& t) { return t.levels() <= kGpuTextureLevels; };
  const auto layersFit = [&](const RtTerrainMaterial& m) { return std::all_of(m.layers().begin(), m.layers().end(), fits); };
  return std::all_of(scene.textures().begin(), scene.textures().end(), fits) &&
         std::all_of(scene.terrains().begin(), scene.terrains().end(), layersFit);
}

GpuTextureSet flattenTextures(const RtScene& scene) {
  GpuTextureSet out;
  for (const RtTexture& t : scene.textures()) append(t, out);
  for (const RtTerrainMaterial& terrain : scene.terrains()) {
    GpuTerrain& g = out.terrains.emplace_back();
    for (int i = 0; i < 3; ++i) {
      g.layers[i] = int(out.textures.size());
      append(terrain.layers()[std::size_t(i)], out);
    }
    g.originYHeightScale = glm::dvec2(terrain.originY(), double(terrain.heightScale()));
  }
  return out;
}

}  // namespace engine::rt
