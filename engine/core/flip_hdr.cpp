// HDR-FLIP (Eurographics 2021): LDR-FLIP at each exposure a viewer might pick,
// through a tone map, keeping each pixel's worst. The range of exposures comes from
// the reference image, as the paper chooses it. And what every FLIP map shares:
// its mean over a mask, and its picture.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/flip.h"

namespace engine {
namespace {

// Each tone map but Reinhard's as the rational curve
// (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5) of each channel. Reinhard's row is
// x / (x + 1), used only to find the exposure range (the map itself scales by
// luminance).
using Curve = std::array<float, 6>;
constexpr Curve kReinhardCurve{0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
// Narkowicz's ACES fit x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) of 0.6 x: the
// fit was made for an input already scaled by 0.6, which HDR-FLIP's exposures replace.
constexpr Curve kAcesCurve{0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};
// Hable's Uncharted 2 curve, as a rational fit.
constexpr Curve kHableCurve{0.231683f, 0.013791f, 0.0f, 0.18f, 0.3f, 0.018f};

const Curve& curveOf(ToneMapper toneMapper) {
  switch (toneMapper) {
    case ToneMapper::Reinhard: return kReinhardCurve;
    case ToneMapper::Hable: return kHableCurve;
    case ToneMapper::Aces: break;
  }
  return kAcesCurve;
}

float luminance(const float* rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

// The input x at which the curve reaches 0.85, the paper's "bright but not
// clipped": the larger root of the curve's equation in x.
float inputGiving085(const Curve& k) {
  const float t = 0.85f;
  const float a = k[0] - t * k[3], b = k[1] - t * k[4], c = k[2] - t * k[5];
  if (a == 0.0f) return -c / b;
  const float mid = -0.5f * (b / a);
  return mid + std::sqrt(mid * mid - c / a);
}

Status checkRange(const ExposureRange& range) {
  if (!std::isfinite(range.start) || !std::isfinite(range.stop) || range.start > range.stop || range.count < 2)
    return makeError("the exposure range must be finite, start <= stop, with at least 2 exposures; got " +
                     std::to_string(range.start) + " to " + std::to_string(range.stop) + " in " +
                     std::to_string(range.count));
  return Ok{};
}

}  // namespace

ExposureRange flipExposureRange(const FloatImage& reference, ToneMapper toneMapper) {
  const size_t count = size_t(reference.width) * size_t(reference.height);
  std::vector<float> luminances(count);
  float brightest = 0.0f, dimmest = 0.0f;  // dimmest: the smallest positive one
  for (size_t i = 0; i < count; ++i) {
    const float y = luminance(&reference.rgb[i * 3]);
    luminances[i] = y;
    brightest = std::max(brightest, y);
    if (y > 0.0f && (dimmest == 0.0f || y < dimmest)) dimmest = y;
  }
  ExposureRange range;
  if (!(brightest > 0.0f)) return range;  // black: exposure 0, twice
  // The upper median, as the reference picks it.
  const auto middle = luminances.begin() + std::ptrdiff_t(count / 2);
  std::nth_element(luminances.begin(), middle, luminances.end());
  const float median = *middle > 0.0f ? *middle : dimmest;
  const float x = inputGiving085(curveOf(toneMapper));
  range.start = std::log2(x / brightest);
  range.stop = std::log2(x / median);
  range.count = int(std::max(2.0f, std::ceil(range.stop - range.start)));
  return range;
}

FloatImage flipToneMapped(const FloatImage& image, float exposure, ToneMapper toneMapper) {
  FloatImage out = image;
  const float scale = std::pow(2.0f, exposure);
  const Curve& k = curveOf(toneMapper);
  for (size_t i = 0; i < out.rgb.size(); i += 3) {
    float* c = &out.rgb[i];
    for (int j = 0; j < 3; ++j) c[j] = c[j] * scale;
    if (toneMapper == ToneMapper::Reinhard) {
      const float factor = 1.0f / (1.0f + luminance(c));
      for (int j = 0; j < 3; ++j) c[j] = c[j] * factor;
    } else {
      for (int j = 0; j < 3; ++j) c[j] = (c[j] * c[j] * k[0] + c[j] * k[1] + k[2]) / (c[j] * c[j] * k[3] + c[j] * k[4] + k[5]);
    }
    for (int j = 0; j < 3; ++j) c[j] = c[j] > 0.0f ? (c[j] < 1.0f ? c[j] : 1.0f) : 0.0f;
  }
  return out;
}

Result<HdrFlip> hdrFlip(const FloatImage& reference, const FloatImage& test, const HdrFlipOptions& options) {
  if (reference.width != test.width || reference.height != test.height)
    return makeError("images differ in size: " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + " vs " + std::to_string(test.width) + "x" +
                     std::to_string(test.height));
  HdrFlip result;
  result.exposures = options.exposures ? *options.exposures : flipExposureRange(reference, options.toneMapper);
  if (auto s = checkRange(result.exposures); !s) return s.error();
  for (int i = 0; i < result.exposures.count; ++i) {
    const float exposure = result.exposures.at(i);
    auto map = ldrFlip(flipToneMapped(reference, exposure, options.toneMapper),
                       flipToneMapped(test, exposure, options.toneMapper), options.ppd);
    if (!map) return map.error();
    if (i == 0) {
      result.map = std::move(*map);
      continue;
    }
    for (size_t p = 0; p < map->error.size(); ++p) result.map.error[p] = std::max(result.map.error[p], map->error[p]);
  }
  return result;
}

Result<double> flipMean(const FlipMap& map, const PixelMask* mask) {
  if (map.error.empty()) return makeError("empty FLIP map");
  if (auto s = checkMaskSize(mask, map.width, map.height); !s) return s.error();
  double sum = 0.0;
  for (size_t i = 0; i < map.error.size(); ++i)
    if (counts(mask, i)) sum += map.error[i];
  return sum / double(mask ? mask->count : map.error.size());
}

Image flipMapImage(const FlipMap& map) {
  Image out(map.width, map.height);
  for (size_t i = 0; i < map.error.size(); ++i) {
    const float v = map.error[i];
    const float e = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;  // NaN gives 0
    const auto byte = static_cast<std::uint8_t>(255.0f * e + 0.5f);
    std::uint8_t* p = &out.pixels[i * 4];
    p[0] = p[1] = p[2] = byte;
    p[3] = 255;
  }
  return out;
}

}  // namespace engine
