#include "raytrace/terrain_material.h"

#include <algorithm>
#include <stdexcept>

#include "terrain/materials.h"

namespace engine::rt {
namespace {

// The GPU uploads the layer images flipped (gl::Texture::fromImage): uv (0, 0) is
// the bottom-left texel.
RtTexture layerTexture(terrain::TerrainLayer layer) {
  return RtTexture(terrain::makeLayerImage(layer, terrain::kLayerImageSize), TextureOrigin::BottomLeft);
}

}  // namespace

RtTerrainMaterial::RtTerrainMaterial(double originY, float heightScale)
    : layers_{layerTexture(terrain::TerrainLayer::Grass), layerTexture(terrain::TerrainLayer::Rock),
              layerTexture(terrain::TerrainLayer::Snow)},
      originY_(originY),
      heightScale_(std::max(heightScale, 1e-3f)) {
  // sample() reads every layer at the first one's taps: a layer made otherwise would
  // be read at texels it may not have.
  if (!layers_[1].tapsLike(layers_[0]) || !layers_[2].tapsLike(layers_[0])) {
    throw std::logic_error("RtTerrainMaterial: the layer images differ in size, wrap or mapping");
  }
}

TerrainLayerSample RtTerrainMaterial::sample(glm::vec2 uv, float footprint, double y, float normalY) const {
  // Two scales of each layer break up visible repetition (terrain_layers.glsl).
  const glm::vec2 uvFar = uv * terrain::kLayerFarScale;
  const float footprintFar = footprint * terrain::kLayerFarScale;
  // The three images are made alike (tapsLike), so each scale's taps are found once
  // and read in each layer: what sample() gives per layer, bit for bit.
  const RtTexture::Taps near = layers_[0].taps(uv, footprint), far = layers_[0].taps(uvFar, footprintFar);
  const auto at = [&](int layer, const RtTexture::Taps& taps) { return glm::vec3(layers_[std::size_t(layer)].read(taps)); };
  // The blend is the rasterizer's text (common/terrain_layers.glsl).
  const terrain::TerrainLayers t = terrain::terrainLayersOf(at(0, near), at(0, far), at(1, near), at(1, far),
                                                            at(2, near), float(y - originY_) / heightScale_,
                                                            1.0f - normalY);
  return TerrainLayerSample{t.albedo, t.roughness, t.specular};
}

}  // namespace engine::rt
