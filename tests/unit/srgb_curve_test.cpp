// core/srgb_curve.h: the exact bytes of the sRGB curve, and the table the shaders
// look them up in, which must give the same byte for every float in [0, 1].
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "core/srgb_curve.h"

using namespace engine;

namespace {

// The curve in long double, rounded: an independent restatement of srgbByte.
int referenceByte(float v) {
  const long double x = v;
  const long double s = x <= 0.0031308L ? 12.92L * x : 1.055L * std::pow(x, 1.0L / 2.4L) - 0.055L;
  return int(std::lround(255.0L * s));
}

}  // namespace

TEST(SrgbCurve, EndsAndOutsideValues) {
  EXPECT_EQ(srgbByte(0.0f), 0);
  EXPECT_EQ(srgbByte(1.0f), 255);
  EXPECT_EQ(srgbByte(-1.0f), 0);
  EXPECT_EQ(srgbByte(2.0f), 255);
  EXPECT_EQ(srgbByte(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(srgbByte(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(srgbByte(0.5f), 188);  // 187.52
  EXPECT_EQ(srgbByte(0.0031308f), 10);  // the knee: 10.3 from either side
}

// Every byte step, and every float within 4096 ulps of it on either side: where a
// table or a formula that is almost right goes wrong.
TEST(SrgbCurve, TableMatchesTheCurveAroundEveryStep) {
  const std::vector<float> table = srgbEncodeTable();
  ASSERT_EQ(table.size(), size_t(2 * kSrgbTableBins));
  int steps = 0;
  for (int bin = 0; bin < kSrgbTableBins; ++bin) {
    const float threshold = table[size_t(2 * bin + 1)];
    if (threshold > 1.0f) continue;
    ++steps;
    const std::uint32_t at = std::bit_cast<std::uint32_t>(threshold);
    ASSERT_GT(srgbByte(threshold), srgbByte(std::bit_cast<float>(at - 1))) << "bin " << bin;
    for (std::uint32_t bits = at - 4096; bits <= at + 4096; ++bits) {
      const float v = std::bit_cast<float>(bits);
      ASSERT_EQ(srgbByteFromTable(table, v), srgbByte(v)) << "v " << v;
      ASSERT_EQ(srgbByte(v), referenceByte(v)) << "v " << v;
    }
  }
  EXPECT_EQ(steps, 255);  // one bin for each step from 0 to 255
}

// A stride through all the floats of [0, 1] (subnormals included), and random
// values: the table, the curve and the long-double curve agree everywhere.
TEST(SrgbCurve, TableMatchesTheCurveEverywhere) {
  const std::vector<float> table = srgbEncodeTable();
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
  for (std::uint32_t bits = 0; bits <= one; bits += 211) {
    const float v = std::bit_cast<float>(bits);
    ASSERT_EQ(srgbByteFromTable(table, v), srgbByte(v)) << "v " << v;
  }
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < 2'000'000; ++i) {
    const float v = uniform(rng);
    ASSERT_EQ(srgbByteFromTable(table, v), srgbByte(v)) << "v " << v;
    ASSERT_EQ(srgbByte(v), referenceByte(v)) << "v " << v;
  }
  EXPECT_EQ(srgbByteFromTable(table, 1.0f), 255);
}

// Each bin starts at the byte the one before it ended on: the bytes rise by one step
// at a time, through every byte from 0 to 255.
TEST(SrgbCurve, BinsStartWhereTheLastOneEnded) {
  const std::vector<float> table = srgbEncodeTable();
  int byte = 0;
  for (int bin = 0; bin < kSrgbTableBins; ++bin) {
    ASSERT_EQ(int(table[size_t(2 * bin)]), byte) << "bin " << bin;
    byte += table[size_t(2 * bin + 1)] <= 1.0f ? 1 : 0;
  }
  EXPECT_EQ(byte, 255);
}
