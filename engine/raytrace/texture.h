#pragma once
// A base colour texture as the rasterizer samples it, for the ray tracer: texels
// decoded from sRGB to linear before filtering (GL does that for SRGB8_ALPHA8),
// bilinear between texel centres, wrap repeat (GL's default, which every texture of
// the rasterizer uses, glTF's default too), and mipmaps as glGenerateMipmap makes
// them (each level the 2x2 average of the one above, in linear), sampled trilinearly
// (GL_LINEAR_MIPMAP_LINEAR) at the level a ray cone's footprint picks.
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"

namespace engine::rt {

// Which image row uv v = 0 reads: glTF textures are uploaded as they are (v = 0 is the
// top row), the scene file's textures flipped (v = 0 is the bottom row).
enum class TextureOrigin { TopLeft, BottomLeft };
// Colour images are sRGB-encoded; data images (glTF's metallic-roughness) are not.
enum class TextureEncoding { Srgb, Linear };

class RtTexture {
 public:
  RtTexture(const Image& image, TextureOrigin origin, TextureEncoding encoding = TextureEncoding::Srgb);

  // Linear RGB at uv (repeating outside [0, 1)). `footprint`: the width of the
  // pixel's footprint in uv units (0: the full-resolution level, as when magnified);
  // its log2 in texels is GL's level of detail.
  glm::vec3 sample(glm::vec2 uv, float footprint = 0.0f) const;
  // The same with the alpha channel (linear, as GL reads it; not sRGB-decoded).
  glm::vec4 sampleRgba(glm::vec2 uv, float footprint = 0.0f) const;

  int width() const { return levels_[0].width; }
  int height() const { return levels_[0].height; }
  int levels() const { return int(levels_.size()); }

 private:
  struct Level {
    int width = 1, height = 1;
    std::vector<glm::vec4> texels;  // linear RGB and alpha, rows with v = 0 first
  };
  static Level halve(const Level& above);
  static glm::vec4 bilinear(const Level& level, glm::vec2 uv);

  std::vector<Level> levels_;
};

}  // namespace engine::rt
