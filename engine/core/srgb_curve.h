#pragma once
// The display's end of the pipeline, once for every renderer: the byte an 8-bit
// display value takes, rounded from the exact curves (evaluated in double), and
// tables that let a shader give the same bytes without evaluating them: a fetch and
// a compare a channel, where the float formulas they replace (pow() and the tone
// map's division, per fragment) were not exact: the GPU's float pow() gave 254
// where the curve gives 255 at 0.99554, and the C++ float pow() other bytes again.
// The GLSL, the clear colour and the tracers now take the same bytes.
//
// A table has bins of equal width from 0 over [0, domain); bin i holds the byte of
// its lowest value and the least float of the bin that takes the next byte
// (infinity where none does). Bins are narrower than the closest two byte steps, so
// that a bin holds at most one step (the tables check it when they are made), and
// as many as a power of two over the domain, so that a value's bin is exact.
#include <cstdint>
#include <vector>

namespace engine {

struct DisplayTable {
  float domain = 1.0f;        // values at or above it take the last bin
  std::vector<float> texels;  // two a bin: the byte (as a float) and the threshold
  int bins() const { return int(texels.size() / 2); }
  // The lookup common/output.glsl's tableByte makes (here for the tests): the bin of
  // min(v, domain), its byte, plus one from its threshold on. v >= 0.
  std::uint8_t lookup(float v) const;
};

// Narkowicz's fit of the ACES filmic curve (2015), render.toneMap "aces": one text for
// every renderer's C++ (float, glm::vec3, and double for the exact tables);
// common/output.glsl's toneMapped is its GLSL twin.
template <typename T>
T acesFit(T x) {
  return (x * (T(2.51) * x + T(0.03))) / (x * (T(2.43) * x + T(0.59)) + T(0.14));
}

// round(255 * srgb(clamp(v, 0, 1))), exactly; NaN gives 0.
std::uint8_t srgbByte(float v);
// The same after Narkowicz's ACES fit (render.toneMap "aces"), clamped to 1: what a
// direct-output fragment writes for radiance x times the exposure.
std::uint8_t acesSrgbByte(float x);

// srgbByte over [0, 1] in 4096 bins (the closest steps are 3.0e-4 apart, at the
// curve's knee); the post pass and the tone maps other than ACES.
const DisplayTable& srgbTable();
// acesSrgbByte over [0, 8) in 16384 bins (steps 6.2e-4 apart at the closest, near
// x = 0.009; x = 6.38 and above give 255).
const DisplayTable& acesSrgbTable();

}  // namespace engine
