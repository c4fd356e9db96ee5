#pragma once
// A base colour texture as the rasterizer samples it, for the ray tracer: texels
// decoded from sRGB to linear before filtering (GL does that for SRGB8_ALPHA8),
// bilinear between texel centres, wrap repeat (GL's default, which every texture of
// the rasterizer uses, glTF's default too). Only the full-resolution level: the
// rasterizer's mipmaps average distant texels, which a single ray cannot know
// without ray differentials, so far-away texture detail aliases here.
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"

namespace engine::rt {

// Which image row uv v = 0 reads: glTF textures are uploaded as they are (v = 0 is the
// top row), the scene file's textures flipped (v = 0 is the bottom row).
enum class TextureOrigin { TopLeft, BottomLeft };

class RtTexture {
 public:
  RtTexture(const Image& srgb, TextureOrigin origin);

  // Linear RGB at uv (repeating outside [0, 1)).
  glm::vec3 sample(glm::vec2 uv) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 1, height_ = 1;
  std::vector<glm::vec3> texels_;  // linear, rows with v = 0 first
};

}  // namespace engine::rt
