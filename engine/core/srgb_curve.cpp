#include "core/srgb_curve.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace engine {
namespace {

double srgbExact(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

// The least float in [lo, hi] whose byte exceeds `byte`, by bisection over the
// floats' bit patterns (positive floats order as their bits do); hi's byte must.
float firstAbove(float lo, float hi, std::uint8_t byte) {
  std::uint32_t a = std::bit_cast<std::uint32_t>(lo), b = std::bit_cast<std::uint32_t>(hi);
  while (a < b) {
    const std::uint32_t mid = a + (b - a) / 2;
    if (srgbByte(std::bit_cast<float>(mid)) > byte) {
      b = mid;
    } else {
      a = mid + 1;
    }
  }
  return std::bit_cast<float>(a);
}

}  // namespace

std::uint8_t srgbByte(float v) {
  if (!(v > 0.0f)) return 0;
  return std::uint8_t(std::lround(255.0 * srgbExact(std::min(double(v), 1.0))));
}

std::vector<float> srgbEncodeTable() {
  std::vector<float> table;
  table.reserve(2 * kSrgbTableBins);
  for (int i = 0; i < kSrgbTableBins; ++i) {
    // Bin i is [i, i + 1) / bins; the last one also holds 1.
    const float lo = float(i) / float(kSrgbTableBins);
    const float hi = i + 1 == kSrgbTableBins ? 1.0f : std::nextafter(float(i + 1) / float(kSrgbTableBins), 0.0f);
    const std::uint8_t byte = srgbByte(lo), last = srgbByte(hi);
    if (last > byte + 1) throw std::logic_error("srgbEncodeTable: a bin holds two byte steps");
    table.push_back(float(byte));
    table.push_back(last > byte ? firstAbove(lo, hi, byte) : 2.0f);
  }
  return table;
}

std::uint8_t srgbByteFromTable(const std::vector<float>& table, float v) {
  const int bin = std::min(int(v * float(kSrgbTableBins)), kSrgbTableBins - 1);
  const float byte = table[size_t(2 * bin)], threshold = table[size_t(2 * bin + 1)];
  return std::uint8_t(byte + (v >= threshold ? 1.0f : 0.0f));
}

}  // namespace engine
