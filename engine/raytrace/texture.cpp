#include "raytrace/texture.h"

#include "asset/texture_transform.h"
#include "core/linear_image.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace engine::rt {
namespace {

const std::array<float, 256>& decodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// GL's wrap of texel index i of n (OpenGL 4.5 core, 8.14.2): repeat; clamp to the
// edge texel; mirrored repeat, (n - 1) - mirror((i mod 2n) - n) with mirror(a) = a
// for a >= 0, -(1 + a) otherwise.
int wrapIndex(int i, int n, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::ClampToEdge: return std::clamp(i, 0, n - 1);
    case TextureWrap::MirroredRepeat: {
      const int a = wrapTexel(i, 2 * n) - n;
      return (n - 1) - (a >= 0 ? a : -(1 + a));
    }
    case TextureWrap::Repeat: break;
  }
  return wrapTexel(i, n);
}

// The two texels a bilinear tap reads, i and i + 1, wrapped, for i = floor(r * n - 0.5)
// of a coordinate r that reduce() has brought into [0, 1] (two periods for mirrored
// repeat): i is then in [-1, n - 1] (r * n - 0.5 is exact at the ends for any side
// an image may have, at most 16384), so repeat and clamp need no division, only a
// check at each edge: the same indices as wrapIndex gives, tested bit for bit.
using TexelPair = RtTexture::TexelPair;
inline TexelPair wrapPair(int i, int n, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::Repeat: return {i < 0 ? n - 1 : i, i + 1 < n ? i + 1 : 0};
    case TextureWrap::ClampToEdge: return {std::max(i, 0), std::min(i + 1, n - 1)};
    case TextureWrap::MirroredRepeat: break;
  }
  return {wrapIndex(i, n, mode), wrapIndex(i + 1, n, mode)};
}

// A coordinate reduced to one period of its wrap (two for mirrored repeat), so that
// large uv (a plane's tiling far from the origin) keep their fraction's precision;
// clamping to [0, 1] picks the same edge texels as CLAMP_TO_EDGE does beyond them.
float reduce(float x, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::ClampToEdge: return std::clamp(x, 0.0f, 1.0f);
    case TextureWrap::MirroredRepeat: return x - 2.0f * std::floor(0.5f * x);
    case TextureWrap::Repeat: break;
  }
  return x - std::floor(x);
}

}  // namespace

// The next mipmap level: floor(size / 2), at least 1, each texel the average of the
// 2x2 block above it (a single row or column at an odd edge is averaged as it is).
RtTexture::Level RtTexture::halve(const Level& above) {
  Level level;
  level.width = std::max(1, above.width / 2);
  level.height = std::max(1, above.height / 2);
  level.texels.resize(std::size_t(level.width) * std::size_t(level.height));
  const auto at = [&](int x, int y) {
    return above.texels[std::size_t(std::min(y, above.height - 1)) * std::size_t(above.width) +
                        std::size_t(std::min(x, above.width - 1))];
  };
  for (int y = 0; y < level.height; ++y) {
    for (int x = 0; x < level.width; ++x) {
      level.texels[std::size_t(y) * std::size_t(level.width) + std::size_t(x)] =
          0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
    }
  }
  return level;
}

RtTexture::RtTexture(const Image& image, TextureOrigin origin, TextureEncoding encoding) {
  Level base;
  if (image.empty()) {
    base.texels.assign(1, glm::vec4(1.0f));
    levels_.push_back(std::move(base));
    return;
  }
  base.width = image.width;
  base.height = image.height;
  base.texels.resize(std::size_t(base.width) * std::size_t(base.height));
  static const std::array<float, 256> linear = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = float(i) / 255.0f;
    return t;
  }();
  const auto& table = encoding == TextureEncoding::Srgb ? decodeTable() : linear;
  for (int y = 0; y < base.height; ++y) {
    const int row = origin == TextureOrigin::TopLeft ? y : base.height - 1 - y;
    for (int x = 0; x < base.width; ++x) {
      const std::uint8_t* p = &image.pixels[(std::size_t(row) * std::size_t(base.width) + std::size_t(x)) * 4];
      base.texels[std::size_t(y) * std::size_t(base.width) + std::size_t(x)] = {table[p[0]], table[p[1]], table[p[2]], float(p[3]) / 255.0f};
    }
  }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(halve(levels_.back()));
}

RtTexture::LevelTaps RtTexture::levelTaps(int index, glm::vec2 reduced) const {
  const Level& level = levels_[std::size_t(index)];
  LevelTaps taps;
  taps.level = index;
  // Texel centres sit at (i + 0.5) / n.
  const float u = reduced.x * float(level.width) - 0.5f;
  const float v = reduced.y * float(level.height) - 0.5f;
  if (!std::isfinite(u) || !std::isfinite(v)) {
    taps.finite = false;
    return taps;
  }
  const float fu = std::floor(u), fv = std::floor(v);
  taps.tu = u - fu;
  taps.tv = v - fv;
  taps.x = wrapPair(int(fu), level.width, wrapS_);
  taps.y = wrapPair(int(fv), level.height, wrapT_);
  return taps;
}

glm::vec4 RtTexture::bilinear(const LevelTaps& taps) const {
  const Level& level = levels_[std::size_t(taps.level)];
  if (!taps.finite) return level.texels[0];
  const glm::vec4* row0 = level.texels.data() + std::size_t(taps.y.i0) * std::size_t(level.width);
  const glm::vec4* row1 = level.texels.data() + std::size_t(taps.y.i1) * std::size_t(level.width);
  return glm::mix(glm::mix(row0[taps.x.i0], row0[taps.x.i1], taps.tu),
                  glm::mix(row1[taps.x.i0], row1[taps.x.i1], taps.tu), taps.tv);
}

RtTexture& RtTexture::setMapping(int texCoord, const glm::mat3& uvTransform) {
  texCoord_ = texCoord;
  uvTransform_ = uvTransform;
  transformed_ = uvTransform != glm::mat3(1.0f);
  // The transform's area scale, as uvPerMetre measures a footprint (sqrt of areas).
  footprintScale_ = std::sqrt(std::abs(uvTransform[0][0] * uvTransform[1][1] - uvTransform[1][0] * uvTransform[0][1]));
  return *this;
}

glm::vec3 RtTexture::sample(const HitUv& uv, float footprint) const { return glm::vec3(sampleRgba(uv, footprint)); }

glm::vec4 RtTexture::sampleRgba(const HitUv& hitUv, float footprint) const { return read(taps(hitUv, footprint)); }

RtTexture::Taps RtTexture::taps(const HitUv& hitUv, float footprint) const {
  glm::vec2 uv = texCoord_ == 1 ? hitUv.uv1 : hitUv.uv0;
  if (transformed_) {
    uv = transformUv(uvTransform_, uv);
    footprint *= footprintScale_;
  }
  const float texels = footprint * float(std::max(width(), height()));
  const float lod = texels > 1.0f ? std::min(std::log2(texels), float(levels() - 1)) : 0.0f;
  uv = {reduce(uv.x, wrapS_), reduce(uv.y, wrapT_)};
  Taps taps;
  if (!(lod > 0.0f)) {
    taps.a = levelTaps(0, uv);
    return taps;
  }
  const int below = int(lod);
  taps.t = lod - float(below);
  taps.a = levelTaps(below, uv);
  if (taps.t > 0.0f) taps.b = levelTaps(below + 1, uv);
  return taps;
}

glm::vec4 RtTexture::read(const Taps& taps) const {
  const glm::vec4 a = bilinear(taps.a);
  return taps.t > 0.0f ? glm::mix(a, bilinear(taps.b), taps.t) : a;
}

bool RtTexture::tapsLike(const RtTexture& other) const {
  // The levels follow from the size, the transform's scale from the transform.
  return width() == other.width() && height() == other.height() && wrapS_ == other.wrapS_ &&
         wrapT_ == other.wrapT_ && texCoord_ == other.texCoord_ && uvTransform_ == other.uvTransform_;
}

}  // namespace engine::rt
