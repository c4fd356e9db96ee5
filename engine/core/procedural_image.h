#pragma once
// Procedural images, made the same way for the rasterizer and the ray tracer.
#include <glm/glm.hpp>

#include "core/image.h"

namespace engine {

// `cells` x `cells` checkerboard of two colours, `size` pixels square.
Image makeChecker(int size, int cells, glm::u8vec3 a, glm::u8vec3 b);
// Square tiles with darker grout lines and a subtle per-tile tint, like brick or tile.
Image makeTiles(int size, int tiles, glm::u8vec3 tile, glm::u8vec3 grout);

}  // namespace engine
