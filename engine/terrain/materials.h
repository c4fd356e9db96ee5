#pragma once
// The terrain's material layers as tiling images made at start-up: no texture
// files to ship, and the same bytes on every machine.
#include <array>

#include <glm/glm.hpp>

#include "core/image.h"

namespace engine::terrain {

enum class TerrainLayer { Grass, Rock, Snow };
inline constexpr std::array<TerrainLayer, 3> kTerrainLayers{TerrainLayer::Grass, TerrainLayer::Rock,
                                                            TerrainLayer::Snow};
// World metres one repeat of a layer's image covers.
inline constexpr float kLayerTileMetres = 8.0f;
// The side of the layer images both renderers make (the GPU's mip level 0).
inline constexpr int kLayerImageSize = 256;

// A `size` x `size` RGBA image (size a power of two, >= 16) that tiles seamlessly:
// its noise lattice wraps at the image edge.
Image makeLayerImage(TerrainLayer layer, int size);

// terrain.vert's u_uvOffset: the camera's offset from the terrain origin in tiles,
// reduced to [0, 1) in double, so that the camera-relative layer uvs
// (xz / kLayerTileMetres + this) stay small and exact far from the origin.
glm::vec2 layerUvOffset(const glm::dvec3& cameraFromOrigin);

// How the layers blend: shaders/common/terrain_layers.glsl, the rasterizer's and the
// GPU tracers' text, compiled as C++ (terrainLayersOf, terrainLayerWeights).
namespace layertext {
// GLSL's built-ins and types, for the included text only (as core/brdf.h does).
using glm::dot;
using glm::max;
using glm::mix;
using glm::smoothstep;
using glm::vec3;

#define BRDF_INLINE inline
#include "common/terrain_layers.glsl"
#undef BRDF_INLINE
}  // namespace layertext
using layertext::TerrainLayers;
using layertext::terrainLayersOf;
// The far scale's uv (uvFar = uv * this) and the classic highlight's exponent.
inline const float kLayerFarScale = layertext::TERRAIN_FAR_LAYER_SCALE;
inline const float kLayerShininess = layertext::TERRAIN_LAYER_SHININESS;

// The (grass, rock, snow) weights, summing to one (the text's terrainLayerWeights).
inline glm::vec3 layerWeights(float height01, float slope, float jitter) {
  return layertext::terrainLayerWeights(height01, slope, jitter);
}

}  // namespace engine::terrain
