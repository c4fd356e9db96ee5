#pragma once
// The terrain's material layers as tiling images made at start-up: no texture
// files to ship, and the same bytes on every machine.
#include <array>

#include "core/image.h"

namespace engine::terrain {

enum class TerrainLayer { Grass, Rock, Snow };
inline constexpr std::array<TerrainLayer, 3> kTerrainLayers{TerrainLayer::Grass, TerrainLayer::Rock,
                                                            TerrainLayer::Snow};
// World metres one repeat of a layer's image covers.
inline constexpr float kLayerTileMetres = 8.0f;

// A `size` x `size` RGBA image (size a power of two, >= 16) that tiles seamlessly:
// its noise lattice wraps at the image edge.
Image makeLayerImage(TerrainLayer layer, int size);

}  // namespace engine::terrain
