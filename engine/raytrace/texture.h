#pragma once
// A base colour texture as the rasterizer samples it, for the ray tracer: texels
// decoded from sRGB to linear before filtering (GL does that for SRGB8_ALPHA8),
// bilinear between texel centres, wrapped in s and t as GL wraps (glTF's REPEAT,
// CLAMP_TO_EDGE, MIRRORED_REPEAT; repeat by default), and mipmaps as
// glGenerateMipmap makes them (each level the 2x2 average of the one above, in
// linear), sampled trilinearly (GL_LINEAR_MIPMAP_LINEAR) at the level a ray cone's
// footprint picks, whatever the glTF sampler's filters (the tracer's own filtering).
//
// A texture of a glTF material slot also knows where it is sampled: the hit's uv set
// (texCoord) through the slot's KHR_texture_transform matrix, the very matrix the
// rasterizer gets as a uniform (asset/texture_transform.h).
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "core/image.h"

namespace engine::rt {

// A hit's texture coordinates: glTF's TEXCOORD_0 and TEXCOORD_1 (the same where a
// surface has only one set, as analytic shapes), and its vertex colour (COLOR_0,
// white where the mesh has none), which the material's colour and alpha take.
struct HitUv {
  glm::vec2 uv0{0.0f}, uv1{0.0f};
  glm::vec4 color{1.0f};
  HitUv() = default;
  HitUv(glm::vec2 uv) : uv0(uv), uv1(uv) {}  // NOLINT: one set is both
  HitUv(glm::vec2 a, glm::vec2 b, glm::vec4 c = glm::vec4(1.0f)) : uv0(a), uv1(b), color(c) {}
};

// Which image row uv v = 0 reads: glTF textures are uploaded as they are (v = 0 is the
// top row), the scene file's textures flipped (v = 0 is the bottom row).
enum class TextureOrigin { TopLeft, BottomLeft };
// Colour images are sRGB-encoded; data images (glTF's metallic-roughness) are not.
enum class TextureEncoding { Srgb, Linear };

class RtTexture {
 public:
  RtTexture(const Image& image, TextureOrigin origin, TextureEncoding encoding = TextureEncoding::Srgb);

  // The glTF sampler's wrap modes (its filters are not the tracer's business).
  RtTexture& setWrap(TextureWrap s, TextureWrap t) {
    wrapS_ = s;
    wrapT_ = t;
    return *this;
  }
  // The material slot's uv set (0 or 1) and KHR_texture_transform matrix.
  RtTexture& setMapping(int texCoord, const glm::mat3& uvTransform);

  // Linear RGB at the hit's uv (its set, through the transform, wrapped).
  // `footprint`: the width of the pixel's footprint in units of TEXCOORD_0 (0: the
  // full-resolution level, as when magnified), scaled here as the transform scales
  // uv; its log2 in texels is GL's level of detail. (Set 1 takes set 0's footprint:
  // the cone's width is only known in set 0's units.)
  glm::vec3 sample(const HitUv& uv, float footprint = 0.0f) const;
  // The same with the alpha channel (linear, as GL reads it; not sRGB-decoded).
  glm::vec4 sampleRgba(const HitUv& uv, float footprint = 0.0f) const;
  // At one uv standing for both sets (analytic shapes, the terrain's layers).
  glm::vec3 sample(glm::vec2 uv, float footprint = 0.0f) const { return sample(HitUv(uv), footprint); }
  glm::vec4 sampleRgba(glm::vec2 uv, float footprint = 0.0f) const { return sampleRgba(HitUv(uv), footprint); }

  // Where a sample at (uv, footprint) reads: its mipmap levels, and on each the two
  // texel columns and rows a bilinear tap takes and their weights. The same for every
  // texture of one size, wrap and mapping (tapsLike), so that one sample's taps serve
  // several such textures: the terrain's layers. read(taps(uv, f)) is sampleRgba(uv, f).
  struct TexelPair {
    int i0, i1;
  };
  struct LevelTaps {
    int level = 0;
    bool finite = true;  // false: a coordinate was not finite; the level's first texel
    TexelPair x{0, 0}, y{0, 0};
    float tu = 0.0f, tv = 0.0f;
  };
  struct Taps {
    LevelTaps a, b;  // b is read only where t > 0
    float t = 0.0f;  // the trilinear weight of b
  };
  Taps taps(const HitUv& uv, float footprint = 0.0f) const;
  glm::vec4 read(const Taps& taps) const;
  // Whether this texture's taps are `other`'s for every uv and footprint.
  bool tapsLike(const RtTexture& other) const;

  int width() const { return levels_[0].width; }
  int height() const { return levels_[0].height; }
  int levels() const { return int(levels_.size()); }
  // What the GPU tracer copies (gputrace/gpu_textures.h): each level's size and texels
  // (linear RGBA, rows with v = 0 first), the wrap modes and the mapping.
  glm::ivec2 levelSize(int level) const { return {levels_[std::size_t(level)].width, levels_[std::size_t(level)].height}; }
  const std::vector<glm::vec4>& levelTexels(int level) const { return levels_[std::size_t(level)].texels; }
  TextureWrap wrapS() const { return wrapS_; }
  TextureWrap wrapT() const { return wrapT_; }
  int texCoord() const { return texCoord_; }
  const glm::mat3& uvTransform() const { return uvTransform_; }
  bool transformed() const { return transformed_; }
  float footprintScale() const { return footprintScale_; }

 private:
  struct Level {
    int width = 1, height = 1;
    std::vector<glm::vec4> texels;  // linear RGB and alpha, rows with v = 0 first
  };
  static Level halve(const Level& above);
  // `reduced`: uv through reduce() (the same at every level).
  LevelTaps levelTaps(int level, glm::vec2 reduced) const;
  glm::vec4 bilinear(const LevelTaps& taps) const;

  std::vector<Level> levels_;
  TextureWrap wrapS_ = TextureWrap::Repeat, wrapT_ = TextureWrap::Repeat;
  int texCoord_ = 0;
  glm::mat3 uvTransform_{1.0f};
  bool transformed_ = false;  // uvTransform_ is not the identity
  float footprintScale_ = 1.0f;  // how much the transform scales lengths in uv
};

}  // namespace engine::rt
