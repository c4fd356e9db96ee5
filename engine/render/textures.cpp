#include "render/textures.h"

namespace engine {

gl::Texture uploadTexture(const Image& image, bool srgb) {
  gl::Texture texture =
      gl::Texture::create2D(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height, 0);
  // GL's first row is the bottom one; uv (0,0) then samples the image's bottom-left.
  Image flipped = image;
  flipVertically(flipped);
  texture.uploadRgba8(flipped.pixels.data());
  texture.generateMipmaps();
  texture.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  texture.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  texture.parameter(GL_TEXTURE_WRAP_S, GL_REPEAT);
  texture.parameter(GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

}  // namespace engine
