#pragma once
// The upload of images as mipmapped GL textures (the procedural ones are in core).
#include <glm/glm.hpp>

#include "core/image.h"
#include "core/procedural_image.h"
#include "gl/resources.h"

namespace engine {

// Uploads an RGBA8 image (top row first) as a mipmapped, repeating, trilinear
// texture; `srgb` for colour data. One implementation, in gl (the terrain's layers
// use it too).
inline gl::Texture uploadTexture(const Image& image, bool srgb) { return gl::Texture::fromImage(image, srgb); }

}  // namespace engine
