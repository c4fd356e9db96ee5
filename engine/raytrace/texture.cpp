#include "raytrace/texture.h"

#include <array>
#include <cmath>

namespace engine::rt {
namespace {

// The sRGB transfer function (IEC 61966-2-1), as GL decodes SRGB8 texels.
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

const std::array<float, 256>& decodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// Wraps a texel index into [0, n), for negative indices too.
int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

}  // namespace

RtTexture::RtTexture(const Image& srgb, TextureOrigin origin) {
  if (srgb.empty()) {
    texels_.assign(1, glm::vec3(1.0f));
    return;
  }
  width_ = srgb.width;
  height_ = srgb.height;
  texels_.resize(std::size_t(width_) * std::size_t(height_));
  const auto& table = decodeTable();
  for (int y = 0; y < height_; ++y) {
    const int row = origin == TextureOrigin::TopLeft ? y : height_ - 1 - y;
    for (int x = 0; x < width_; ++x) {
      const std::uint8_t* p = &srgb.pixels[(std::size_t(row) * std::size_t(width_) + std::size_t(x)) * 4];
      texels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)] = {table[p[0]], table[p[1]], table[p[2]]};
    }
  }
}

glm::vec3 RtTexture::sample(glm::vec2 uv) const {
  // Texel centres sit at (i + 0.5) / n; reduce to one period first, so that large uv
  // (a plane's tiling far from the origin) keep their fraction's precision.
  const float u = (uv.x - std::floor(uv.x)) * float(width_) - 0.5f;
  const float v = (uv.y - std::floor(uv.y)) * float(height_) - 0.5f;
  if (!std::isfinite(u) || !std::isfinite(v)) return texels_[0];
  const float fu = std::floor(u), fv = std::floor(v);
  const float tu = u - fu, tv = v - fv;
  const int x0 = wrap(int(fu), width_), x1 = wrap(int(fu) + 1, width_);
  const int y0 = wrap(int(fv), height_), y1 = wrap(int(fv) + 1, height_);
  const auto at = [&](int x, int y) { return texels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tu), glm::mix(at(x0, y1), at(x1, y1), tu), tv);
}

}  // namespace engine::rt
