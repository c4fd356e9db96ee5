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

// How the layers blend, as shaders/terrain.frag shades them (its layerWeights and
// main): the two texture scales, and the roughness and classic highlight per layer.
inline constexpr float kLayerFarScale = 0.173f;                       // uvFar = uv * this
inline constexpr glm::vec3 kLayerRoughness{0.95f, 0.8f, 0.5f};         // dot(w, this)
inline constexpr float kLayerSpecular = 0.02f, kSnowSpecular = 0.25f;  // mix(.., .., w.z)
inline constexpr float kLayerShininess = 24.0f;

// The (grass, rock, snow) weights, summing to one, at `height01` (metres above the
// terrain origin over the height scale), `slope` (1 - n.y of the unit shading
// normal) and `jitter` (rock.r * 2 - 0.5 of the rock layer's linear colour): rock
// where steep, snow high up but not on cliffs, grass elsewhere. The C++ twin of
// layerWeights in shaders/terrain.frag, operation for operation: change both together.
glm::vec3 layerWeights(float height01, float slope, float jitter);

}  // namespace engine::terrain
