#pragma once
// The upload of images as mipmapped GL textures (the procedural ones are in core).
#include <glm/glm.hpp>

#include "core/image.h"
#include "core/procedural_image.h"
#include "gl/resources.h"

namespace engine {

// Uploads an RGBA8 image (top row first) as a mipmapped, repeating, trilinear
// texture; `srgb` for colour data.
gl::Texture uploadTexture(const Image& image, bool srgb);

}  // namespace engine
