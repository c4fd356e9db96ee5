// core/srgb_curve.h: the exact bytes of the display curves (sRGB, and ACES then
// sRGB), and the tables the shaders look them up in, which must give the same byte
// for every float.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "core/srgb_curve.h"

using namespace engine;

namespace {

// The curves in long double, rounded: an independent restatement.
int referenceSrgb(long double v) {
  v = std::clamp(v, 0.0L, 1.0L);
  const long double s = v <= 0.0031308L ? 12.92L * v : 1.055L * std::pow(v, 1.0L / 2.4L) - 0.055L;
  return int(std::lround(255.0L * s));
}
int referenceAces(float x) {
  const long double v = x;
  return referenceSrgb((v * (2.51L * v + 0.03L)) / (v * (2.43L * v + 0.59L) + 0.14L));
}

struct Curve {
  const char* name;
  const DisplayTable& table;
  std::uint8_t (*byteOf)(float);
  int (*reference)(float);
};
const Curve kCurves[] = {{"srgb", srgbTable(), srgbByte, [](float v) { return referenceSrgb(v); }},
                         {"aces+srgb", acesSrgbTable(), acesSrgbByte, referenceAces}};

}  // namespace

TEST(DisplayCurves, EndsAndOutsideValues) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(srgbByte(0.0f), 0);
  EXPECT_EQ(srgbByte(1.0f), 255);
  EXPECT_EQ(srgbByte(-1.0f), 0);
  EXPECT_EQ(srgbByte(2.0f), 255);
  EXPECT_EQ(srgbByte(inf), 255);
  EXPECT_EQ(srgbByte(nan), 0);
  EXPECT_EQ(srgbByte(0.5f), 188);       // 187.52
  EXPECT_EQ(srgbByte(0.0031308f), 10);  // the knee: 10.3 from either side
  EXPECT_EQ(acesSrgbByte(0.0f), 0);
  EXPECT_EQ(acesSrgbByte(-1.0f), 0);
  EXPECT_EQ(acesSrgbByte(nan), 0);
  EXPECT_EQ(acesSrgbByte(6.3f), 254);
  EXPECT_EQ(acesSrgbByte(6.4f), 255);
  EXPECT_EQ(acesSrgbByte(1e30f), 255);
  EXPECT_EQ(acesSrgbByte(inf), 255);
  for (const Curve& c : kCurves) {
    EXPECT_EQ(c.table.lookup(0.0f), 0) << c.name;
    EXPECT_EQ(c.table.lookup(c.table.domain), 255) << c.name;
    EXPECT_EQ(c.table.lookup(1e30f), 255) << c.name;
    EXPECT_EQ(c.table.lookup(inf), 255) << c.name;
  }
}

// Every byte step, and every float within 4096 ulps of it on either side: where a
// table or a formula that is almost right goes wrong.
TEST(DisplayCurves, TablesMatchTheCurvesAroundEveryStep) {
  for (const Curve& c : kCurves) {
    int steps = 0;
    for (int bin = 0; bin < c.table.bins(); ++bin) {
      const float threshold = c.table.texels[size_t(2 * bin + 1)];
      if (std::isinf(threshold)) continue;
      ++steps;
      const std::uint32_t at = std::bit_cast<std::uint32_t>(threshold);
      ASSERT_GT(c.byteOf(threshold), c.byteOf(std::bit_cast<float>(at - 1))) << c.name << " bin " << bin;
      for (std::uint32_t bits = at - 4096; bits <= at + 4096; ++bits) {
        const float v = std::bit_cast<float>(bits);
        ASSERT_EQ(c.table.lookup(v), c.byteOf(v)) << c.name << " v " << v;
        ASSERT_EQ(c.byteOf(v), c.reference(v)) << c.name << " v " << v;
      }
    }
    EXPECT_EQ(steps, 255) << c.name;  // one bin for each step from 0 to 255
  }
}

// A stride through all the floats of the table's domain (subnormals included), and
// random values: the table, the curve and the long-double curve agree everywhere.
TEST(DisplayCurves, TablesMatchTheCurvesEverywhere) {
  for (const Curve& c : kCurves) {
    const std::uint32_t end = std::bit_cast<std::uint32_t>(c.table.domain);
    for (std::uint32_t bits = 0; bits <= end; bits += 1021) {
      const float v = std::bit_cast<float>(bits);
      ASSERT_EQ(c.table.lookup(v), c.byteOf(v)) << c.name << " v " << v;
    }
    std::mt19937 rng(14);
    std::uniform_real_distribution<float> uniform(0.0f, c.table.domain);
    for (int i = 0; i < 200'000; ++i) {
      const float v = uniform(rng);
      ASSERT_EQ(c.table.lookup(v), c.byteOf(v)) << c.name << " v " << v;
      ASSERT_EQ(c.byteOf(v), c.reference(v)) << c.name << " v " << v;
    }
  }
}

// Each bin starts at the byte the one before it ended on: the bytes rise by one step
// at a time, through every byte from 0 to 255.
TEST(DisplayCurves, BinsStartWhereTheLastOneEnded) {
  for (const Curve& c : kCurves) {
    int byte = 0;
    for (int bin = 0; bin < c.table.bins(); ++bin) {
      ASSERT_EQ(int(c.table.texels[size_t(2 * bin)]), byte) << c.name << " bin " << bin;
      byte += std::isinf(c.table.texels[size_t(2 * bin + 1)]) ? 0 : 1;
    }
    EXPECT_EQ(byte, 255) << c.name;
  }
}
