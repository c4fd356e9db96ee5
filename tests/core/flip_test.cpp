// FLIP (core/flip.h) on images small enough to reason about: zero for equal
// images, [0, 1] always, the colour pipeline against the CIE formulas evaluated
// here in double, errors only within the filters' reach, a recorded value for a
// shifted edge, masks that leave out what they should, and HDR-FLIP's exposures.
// NVIDIA's own figures are checked by hand (docs/measuring.md#flip): their test
// images are too large to ship.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/flip.h"

using namespace engine;

namespace {

// The mean of AShiftedEdgeErrsOnlyWithinTheFiltersReach's pair (0.0555787067):
// NVIDIA's FLIP.h gives the same map to the bit and its tool prints 0.055579.
constexpr double kShiftedEdgeMean = 0.0555787;

Image flipSolid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image image(w, h);
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i] = r, image.pixels[i + 1] = g, image.pixels[i + 2] = b, image.pixels[i + 3] = 255;
  }
  return image;
}

// Deterministic noise (a 32-bit LCG), so every run compares the same pixels.
Image flipNoise(int w, int h, std::uint32_t seed) {
  Image image(w, h);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    seed = seed * 1664525u + 1013904223u;
    image.pixels[i] = i % 4 == 3 ? 255 : std::uint8_t(seed >> 24);
  }
  return image;
}

// A grey ramp across x with a dark bar 4 pixels wide from column `bar`.
Image flipRampWithBar(int w, int h, int bar) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto v = std::uint8_t(x >= bar && x < bar + 4 ? 20 : 255 * x / (w - 1));
      std::uint8_t* p = image.at(x, y);
      p[0] = p[1] = p[2] = v, p[3] = 255;
    }
  return image;
}

FloatImage flipGreyHdr(const std::vector<float>& values, int w) {
  FloatImage image;
  image.width = w;
  image.height = int(values.size()) / w;
  for (float v : values) image.rgb.insert(image.rgb.end(), {v, v, v});
  return image;
}

// The colour error of two uniform colours straight from the definitions (CIE
// L*a*b* of sRGB with D65 white, the Hunt scaling, HyAB, q_c = 0.7, the map with
// p_c = 0.4 and p_t = 0.95), in double: a uniform image is unchanged by the
// filters and has no features, so this is FLIP's value at every pixel.
double flipUniformError(std::array<int, 3> a, std::array<int, 3> b) {
  const auto linear = [](int byte) {
    const double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  const double m[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                          {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                          {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
  const auto lab = [&](std::array<double, 3> rgb) {
    std::array<double, 3> f{};
    for (int i = 0; i < 3; ++i) {
      const double white = m[i][0] + m[i][1] + m[i][2];  // XYZ of RGB (1, 1, 1)
      const double t = (m[i][0] * rgb[0] + m[i][1] * rgb[1] + m[i][2] * rgb[2]) / white;
      const double d = 6.0 / 29.0;
      f[size_t(i)] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    }
    const double l = 116 * f[1] - 16;
    return std::array<double, 3>{l, 0.01 * l * 500 * (f[0] - f[1]), 0.01 * l * 200 * (f[1] - f[2])};
  };
  const auto hyab = [](std::array<double, 3> p, std::array<double, 3> q) {
    return std::fabs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
  };
  const double cmax = std::pow(hyab(lab({0, 1, 0}), lab({0, 0, 1})), 0.7);
  const double d = std::pow(hyab(lab({linear(a[0]), linear(a[1]), linear(a[2])}),
                                 lab({linear(b[0]), linear(b[1]), linear(b[2])})),
                            0.7);
  const double knee = 0.4 * cmax;
  return d < knee ? d * 0.95 / knee : 0.95 + (d - knee) / (cmax - knee) * 0.05;
}

double flipMeanOf(const FlipMap& map, const PixelMask* mask = nullptr) {
  auto mean = flipMean(map, mask);
  EXPECT_TRUE(mean.ok());
  return mean.ok() ? *mean : -1.0;
}

}  // namespace

TEST(Flip, DefaultViewerIs67PixelsPerDegree) {
  EXPECT_NEAR(kFlipDefaultPpd, 0.7 * 3840 / 0.7 * std::numbers::pi / 180.0, 1e-4);
  EXPECT_NEAR(kFlipDefaultPpd, 67.02, 0.01);
}

TEST(Flip, EqualImagesGiveZero) {
  const Image a = flipNoise(48, 40, 7);
  auto map = ldrFlip(a, a);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(*std::max_element(map->error.begin(), map->error.end()), 0.0f);
  EXPECT_EQ(flipMeanOf(*map), 0.0);
  const FloatImage hdr = flipGreyHdr(std::vector<float>(48 * 40, 3.5f), 48);
  auto hdrMap = hdrFlip(hdr, hdr);
  ASSERT_TRUE(hdrMap.ok());
  EXPECT_EQ(flipMeanOf(hdrMap->map), 0.0);
}

TEST(Flip, ErrorsAreBetweenZeroAndOne) {
  // Noise against other noise, and the extremes: black against white, red
  // against green, each way round.
  const std::array<std::pair<Image, Image>, 4> pairs{
      std::pair{flipNoise(40, 32, 1), flipNoise(40, 32, 2)},
      std::pair{flipSolid(40, 32, 0, 0, 0), flipSolid(40, 32, 255, 255, 255)},
      std::pair{flipSolid(40, 32, 255, 0, 0), flipSolid(40, 32, 0, 255, 0)},
      std::pair{flipNoise(40, 32, 3), flipSolid(40, 32, 0, 0, 255)}};
  for (const auto& [a, b] : pairs) {
    for (const auto& map : {ldrFlip(a, b), ldrFlip(b, a)}) {
      ASSERT_TRUE(map.ok());
      for (float e : map->error) ASSERT_TRUE(e >= 0.0f && e <= 1.0f) << e;
      EXPECT_GT(flipMeanOf(map.value()), 0.1);
    }
  }
}

TEST(Flip, UniformImagesGiveTheCieColourDistance) {
  // Float against double, and the feature detectors' rounding on a flat image
  // (their weights sum to 0 only to a few ulps; q_f = 0.5 turns 1e-9 into 3e-5 of
  // exponent): the worst of these pairs measured 3.7e-5 away.
  const std::array<std::array<int, 3>, 5> colours{
      {{0, 0, 0}, {255, 255, 255}, {200, 30, 30}, {90, 160, 220}, {128, 128, 128}}};
  for (size_t i = 0; i < colours.size(); ++i) {
    for (size_t j = i + 1; j < colours.size(); ++j) {
      const auto& a = colours[i];
      const auto& b = colours[j];
      auto map = ldrFlip(flipSolid(24, 24, std::uint8_t(a[0]), std::uint8_t(a[1]), std::uint8_t(a[2])),
                         flipSolid(24, 24, std::uint8_t(b[0]), std::uint8_t(b[1]), std::uint8_t(b[2])));
      ASSERT_TRUE(map.ok());
      const double expected = flipUniformError(a, b);
      for (float e : map->error) ASSERT_NEAR(e, expected, 1e-4) << i << " vs " << j;
    }
  }
}

TEST(Flip, AShiftedEdgeErrsOnlyWithinTheFiltersReach) {
  // At 67 ppd the colour filters reach 10 pixels and the feature filters 9; the
  // bars differ in columns 20..25, so columns 36 on must be exactly 0.
  const int w = 64, h = 48;
  auto map = ldrFlip(flipRampWithBar(w, h, 20), flipRampWithBar(w, h, 22));
  ASSERT_TRUE(map.ok());
  for (int y = 0; y < h; ++y) {
    for (int x = 36; x < w; ++x) ASSERT_EQ(map->error[size_t(y * w + x)], 0.0f) << x << "," << y;
    EXPECT_GT(map->error[size_t(y * w + 21)], 0.5f);  // where one image has the bar and the other not
  }
  // The recorded mean; another compiler or libm may round the float steps (exp,
  // pow) differently by an ulp or two a pixel, some 1e-7 of the mean: 1e-5 allows
  // that and nothing else (the bar one pixel further moves it by 0.013).
  EXPECT_NEAR(flipMeanOf(*map), kShiftedEdgeMean, 1e-5);
}

TEST(Flip, AMaskLeavesOutWhatItDoesNotSelect) {
  const int w = 64, h = 32;
  const Image a = flipNoise(w, h, 11);
  Image b = a;
  b.at(5, 5)[0] ^= 0x80;  // an error inside the mask
  // The mask selects columns 0..23.
  Image maskImage = flipSolid(w, h, 0, 0, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 24; ++x) maskImage.at(x, y)[1] = 1;
  auto mask = maskFromImage(maskImage, w, h, "mask.png");
  ASSERT_TRUE(mask.ok());
  EXPECT_EQ(mask->count, size_t(24 * h));

  // An error more than the filters' reach (10 pixels at 67 ppd, SSIM's 5) outside
  // the mask changes no masked figure, and changes the unmasked ones.
  Image c = b;
  for (int y = 0; y < h; ++y) c.at(50, y)[2] ^= 0xff;
  auto withB = ldrFlip(a, b), withC = ldrFlip(a, c);
  ASSERT_TRUE(withB.ok() && withC.ok());
  EXPECT_EQ(flipMeanOf(*withB, &*mask), flipMeanOf(*withC, &*mask));
  EXPECT_LT(flipMeanOf(*withB), flipMeanOf(*withC));
  const auto diffB = compareImages(a, b, 8, &*mask), diffC = compareImages(a, c, 8, &*mask);
  ASSERT_TRUE(diffB.ok() && diffC.ok());
  EXPECT_EQ(diffB->psnr, diffC->psnr);
  EXPECT_EQ(diffB->meanAbs, diffC->meanAbs);
  EXPECT_EQ(diffB->maxAbs, 128);
  EXPECT_EQ(structuralSimilarity(a, b, &*mask).value(), structuralSimilarity(a, c, &*mask).value());
  EXPECT_GT(compareImages(a, b)->psnr, compareImages(a, c)->psnr);

  // The masked mean is the mean over the selected pixels alone.
  double sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 24; ++x) sum += withB->error[size_t(y * w + x)];
  EXPECT_NEAR(flipMeanOf(*withB, &*mask), sum / (24 * h), 1e-12);
  EXPECT_GT(flipMeanOf(*withB, &*mask), flipMeanOf(*withB));  // the error is inside
}

TEST(Flip, BadMasksAndSizesAreErrors) {
  const Image a = flipSolid(8, 6, 1, 2, 3);
  auto small = maskFromImage(flipSolid(4, 6, 255, 255, 255), 8, 6, "small.png");
  ASSERT_FALSE(small.ok());
  EXPECT_EQ(small.error().message, "small.png: the mask is 4x6 pixels, the images 8x6");
  auto black = maskFromImage(flipSolid(8, 6, 0, 0, 0), 8, 6, "black.png");
  ASSERT_FALSE(black.ok());
  EXPECT_NE(black.error().message.find("black.png: the mask selects no pixel"), std::string::npos);
  auto sizes = ldrFlip(a, flipSolid(8, 7, 1, 2, 3));
  ASSERT_FALSE(sizes.ok());
  EXPECT_NE(sizes.error().message.find("8x6 vs 8x7"), std::string::npos);
  auto ppd = ldrFlip(a, a, 0.0f);
  EXPECT_FALSE(ppd.ok());
  auto wholeMask = maskFromImage(flipSolid(8, 6, 9, 9, 9), 8, 6, "m.png");
  ASSERT_TRUE(wholeMask.ok());
  FlipMap other{4, 4, std::vector<float>(16, 0.5f)};
  EXPECT_FALSE(flipMean(other, &*wholeMask).ok());
  EXPECT_FALSE(compareImages(flipSolid(4, 4, 0, 0, 0), flipSolid(4, 4, 0, 0, 0), 8, &*wholeMask).ok());
}

TEST(Flip, ExposureRangeFollowsTheReference) {
  // Luminances 0.25, 0.25, 0.25 and 8: from the exposure that takes 8 to 0.85 through
  // ACES to the one that takes the (upper) median 0.25 there, 5 stops.
  const FloatImage image = flipGreyHdr({0.25f, 8.0f, 0.25f, 0.25f}, 2);
  // The input ACES (applied to 0.6 x) takes to 0.85, solved here in double.
  const double k[6] = {0.36 * 2.51, 0.6 * 0.03, 0.0, 0.36 * 2.43, 0.6 * 0.59, 0.14};
  const double qa = k[0] - 0.85 * k[3], qb = k[1] - 0.85 * k[4], qc = k[2] - 0.85 * k[5];
  const double x = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
  const ExposureRange range = flipExposureRange(image);
  EXPECT_NEAR(range.start, std::log2(x / 8.0), 1e-5);
  EXPECT_NEAR(range.stop, std::log2(x / 0.25), 1e-5);
  EXPECT_EQ(range.count, 5);
  // A black reference falls back to exposure 0.
  const ExposureRange black = flipExposureRange(flipGreyHdr({0, 0, 0, 0}, 2));
  EXPECT_EQ(black.start, 0.0f);
  EXPECT_EQ(black.count, 2);
}

TEST(Flip, HdrFlipIsTheWorstExposure) {
  FloatImage reference = linearFromSrgb(flipNoise(32, 24, 5)), test = linearFromSrgb(flipNoise(32, 24, 6));
  for (float& v : reference.rgb) v *= 40.0f;
  for (float& v : test.rgb) v *= 40.0f;
  HdrFlipOptions options;
  options.exposures = ExposureRange{-3.0f, 1.0f, 3};
  auto hdr = hdrFlip(reference, test, options);
  ASSERT_TRUE(hdr.ok());
  std::vector<float> worst(hdr->map.error.size(), 0.0f);
  for (float exposure : {-3.0f, -1.0f, 1.0f}) {
    auto ldr = ldrFlip(flipToneMapped(reference, exposure, ToneMapper::Aces),
                       flipToneMapped(test, exposure, ToneMapper::Aces));
    ASSERT_TRUE(ldr.ok());
    for (size_t i = 0; i < worst.size(); ++i) worst[i] = std::max(worst[i], ldr->error[i]);
  }
  EXPECT_EQ(hdr->map.error, worst);
  options.exposures = ExposureRange{1.0f, 0.0f, 3};
  EXPECT_FALSE(hdrFlip(reference, test, options).ok());
}

TEST(Flip, HdrFlipDoesNotDependOnTheImagesScale) {
  // The exposures follow the reference, so both images 16 times brighter are seen
  // through exposures 4 stops lower: the same tone-mapped pairs, up to rounding.
  FloatImage reference = linearFromSrgb(flipRampWithBar(40, 24, 10)), test = linearFromSrgb(flipRampWithBar(40, 24, 12));
  for (float& v : reference.rgb) v = v * v * 30.0f;
  for (float& v : test.rgb) v = v * v * 30.0f;
  auto base = hdrFlip(reference, test);
  for (float& v : reference.rgb) v *= 16.0f;
  for (float& v : test.rgb) v *= 16.0f;
  auto brighter = hdrFlip(reference, test);
  ASSERT_TRUE(base.ok() && brighter.ok());
  EXPECT_NEAR(brighter->exposures.start, base->exposures.start - 4.0f, 1e-5);
  EXPECT_EQ(brighter->exposures.count, base->exposures.count);
  EXPECT_GT(flipMeanOf(base->map), 0.01);
  EXPECT_NEAR(flipMeanOf(brighter->map), flipMeanOf(base->map), 1e-5);
}

TEST(Flip, MapPictureIsGrey) {
  const FlipMap map{3, 1, {0.0f, 0.5f, 1.0f}};
  const Image picture = flipMapImage(map);
  EXPECT_EQ(picture.at(0, 0)[0], 0);
  EXPECT_EQ(picture.at(1, 0)[1], 128);
  EXPECT_EQ(picture.at(2, 0)[2], 255);
  EXPECT_EQ(picture.at(2, 0)[3], 255);
}
