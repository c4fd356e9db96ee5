#pragma once
// Procedural images and their upload as mipmapped GL textures.
#include <glm/glm.hpp>

#include "core/image.h"
#include "gl/resources.h"

namespace engine {

// `cells` x `cells` checkerboard of two colours, `size` pixels square.
Image makeChecker(int size, int cells, glm::u8vec3 a, glm::u8vec3 b);
// Square tiles with darker grout lines and a subtle per-tile tint, like brick or tile.
Image makeTiles(int size, int tiles, glm::u8vec3 tile, glm::u8vec3 grout);

// Uploads an RGBA8 image (top row first) as a mipmapped, repeating, trilinear
// texture; `srgb` for colour data. One implementation, in gl (the terrain's layers
// use it too).
inline gl::Texture uploadTexture(const Image& image, bool srgb) { return gl::Texture::fromImage(image, srgb); }

}  // namespace engine
