#include "core/srgb_curve.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace engine {
namespace {

double srgbExact(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

using ByteOf = std::function<std::uint8_t(float)>;

// The least float in [lo, hi] whose byte exceeds `byte`, by bisection over the
// floats' bit patterns (non-negative floats order as their bits do); hi's byte must.
float firstAbove(const ByteOf& byteOf, float lo, float hi, std::uint8_t byte) {
  std::uint32_t a = std::bit_cast<std::uint32_t>(lo), b = std::bit_cast<std::uint32_t>(hi);
  while (a < b) {
    const std::uint32_t mid = a + (b - a) / 2;
    if (byteOf(std::bit_cast<float>(mid)) > byte) {
      b = mid;
    } else {
      a = mid + 1;
    }
  }
  return std::bit_cast<float>(a);
}

// `byteOf` (non-decreasing) in `bins` bins over [0, domain).
DisplayTable makeTable(const ByteOf& byteOf, float domain, int bins) {
  DisplayTable table{domain, {}};
  table.texels.reserve(2 * size_t(bins));
  const float width = domain / float(bins);  // a power of two: bin edges are exact
  for (int i = 0; i < bins; ++i) {
    const float lo = float(i) * width;
    const float hi = std::nextafter(float(i + 1) * width, 0.0f);
    const std::uint8_t byte = byteOf(lo), last = byteOf(hi);
    if (last > byte + 1) throw std::logic_error("display table: a bin holds two byte steps");
    table.texels.push_back(float(byte));
    table.texels.push_back(last > byte ? firstAbove(byteOf, lo, hi, byte) : std::numeric_limits<float>::infinity());
  }
  return table;
}

}  // namespace

std::uint8_t srgbByte(float v) {
  if (!(v > 0.0f)) return 0;
  return std::uint8_t(std::lround(255.0 * srgbExact(std::min(double(v), 1.0))));
}

std::uint8_t acesSrgbByte(float x) {
  if (!(x > 0.0f)) return 0;
  if (std::isinf(x)) return 255;
  return std::uint8_t(std::lround(255.0 * srgbExact(std::min(acesFit<double>(x), 1.0))));
}

std::uint8_t DisplayTable::lookup(float v) const {
  const float x = std::min(v, domain);
  const int bin = std::clamp(int(x * (float(bins()) / domain)), 0, bins() - 1);
  const float byte = texels[size_t(2 * bin)], threshold = texels[size_t(2 * bin + 1)];
  return std::uint8_t(byte + (x >= threshold ? 1.0f : 0.0f));
}

const DisplayTable& srgbTable() {
  static const DisplayTable table = makeTable(srgbByte, 1.0f, 4096);
  return table;
}

const DisplayTable& acesSrgbTable() {
  static const DisplayTable table = makeTable(acesSrgbByte, 8.0f, 16384);
  return table;
}

}  // namespace engine
