#pragma once
// The sRGB output curve, once for every renderer: the byte an 8-bit display value
// takes for a linear value in [0, 1], rounded from the exact curve (IEC 61966-2-1,
// evaluated in double), and the table that lets a shader give the same byte without
// pow(). On llvmpipe pow() is two polynomials a channel, and the curve is applied to
// every fragment a direct-output frame shades: 5-6 ms of a 25 ms frame of 50
// characters (issue 14). The table costs a fetch and a compare a channel and is
// exact, where the float pow() it replaces was not.
//
// The table has kSrgbTableBins bins of equal width over [0, 1]; bin i holds the byte
// of its lowest value and the least float of the bin that takes the next byte (2.0
// where none does). Bins are narrower than the closest two byte steps (3.0e-4 near
// the curve's knee), so a bin holds at most one step; srgbEncodeTable checks it.
#include <cstdint>
#include <vector>

namespace engine {

inline constexpr int kSrgbTableBins = 4096;

// round(255 * srgb(clamp(v, 0, 1))), exactly; NaN gives 0.
std::uint8_t srgbByte(float v);

// Two floats a bin: the byte (as a float) and the threshold.
std::vector<float> srgbEncodeTable();

// The lookup common/output.glsl's srgbEncoded makes, here for the tests: bin
// min(int(v * bins), bins - 1), its byte, plus one from the threshold on.
std::uint8_t srgbByteFromTable(const std::vector<float>& table, float v);

}  // namespace engine
