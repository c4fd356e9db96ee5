#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/image.h"

using namespace engine;

namespace {
Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = image.at(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  return image;
}
std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("engine_unit_" + name)).string();
}
}  // namespace

TEST(Image, IdenticalImagesHaveInfinitePsnr) {
  const Image a = solid(4, 3, 10, 20, 30);
  auto d = compareImages(a, a);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->maxAbs, 0);
  EXPECT_EQ(d->meanAbs, 0.0);
  EXPECT_TRUE(std::isinf(d->psnr));
  EXPECT_EQ(d->shareOver, 0.0);
}

TEST(Image, DifferenceStatistics) {
  Image a = solid(2, 1, 100, 100, 100), b = a;
  b.at(1, 0)[0] = 160;  // one channel of one pixel off by 60
  auto d = compareImages(a, b, 8);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->maxAbs, 60);
  EXPECT_DOUBLE_EQ(d->meanAbs, 60.0 / 6.0);
  EXPECT_DOUBLE_EQ(d->shareOver, 0.5);
  // MSE = 3600 / 6 = 600.
  EXPECT_NEAR(d->psnr, 10.0 * std::log10(255.0 * 255.0 / 600.0), 1e-9);
}

TEST(Image, AlphaIsIgnored) {
  Image a = solid(1, 1, 1, 2, 3), b = a;
  b.at(0, 0)[3] = 0;
  EXPECT_EQ(compareImages(a, b)->maxAbs, 0);
}

TEST(Image, SizeMismatchIsAnError) {
  auto d = compareImages(Image(2, 2), Image(2, 3));
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("2x2 vs 2x3"), std::string::npos);
}

TEST(Image, PngRoundTrip) {
  Image a(3, 2);
  for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = static_cast<std::uint8_t>(i * 11);
  const std::string path = tempPath("roundtrip.png");
  ASSERT_TRUE(writePng(path, a).ok());
  auto b = readPng(path);
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(b->width, 3);
  EXPECT_EQ(b->height, 2);
  EXPECT_EQ(b->pixels, a.pixels);
  std::filesystem::remove(path);
}

TEST(Image, UnwritablePathLeavesNothing) {
  auto s = writePng("/nonexistent-folder/x.png", solid(1, 1, 0, 0, 0));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("/nonexistent-folder/x.png"), std::string::npos);
}

TEST(Image, UnreadableFileNamesThePath) {
  const std::string path = tempPath("not_a_png.png");
  { std::FILE* f = std::fopen(path.c_str(), "wb"); std::fputs("hello", f); std::fclose(f); }
  auto r = readPng(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find(path), std::string::npos);
  std::filesystem::remove(path);
}

TEST(Image, FlipVerticallySwapsRows) {
  Image a(1, 3);
  for (int y = 0; y < 3; ++y) a.at(0, y)[0] = static_cast<std::uint8_t>(y);
  flipVertically(a);
  EXPECT_EQ(a.at(0, 0)[0], 2);
  EXPECT_EQ(a.at(0, 1)[0], 1);
  EXPECT_EQ(a.at(0, 2)[0], 0);
}

// SSIM: 1 for equal images; a uniform brightness shift costs little (structure kept),
// noise of the same mean square error costs much more, and a shift of the whole image
// by a constant leaves the contrast term exactly 1.
TEST(Image, StructuralSimilarityWeighsStructureNotBrightness) {
  Image base(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      auto* p = base.at(x, y);
      p[0] = p[1] = p[2] = std::uint8_t(((x / 8 + y / 8) % 2) ? 130 : 100);  // low contrast
      p[3] = 255;
    }
  }
  EXPECT_DOUBLE_EQ(structuralSimilarity(base, base).value(), 1.0);
  Image brighter = base, noisy = base;
  std::uint32_t state = 1;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      state = state * 1664525u + 1013904223u;
      const int sign = (state >> 31) ? 10 : -10;  // +-10: the same MSE as the shift of 10
      for (int c = 0; c < 3; ++c) {
        brighter.at(x, y)[c] = std::uint8_t(base.at(x, y)[c] + 10);
        noisy.at(x, y)[c] = std::uint8_t(base.at(x, y)[c] + sign);
      }
    }
  }
  EXPECT_NEAR(compareImages(base, brighter)->psnr, compareImages(base, noisy)->psnr, 1e-9);
  const double shifted = structuralSimilarity(base, brighter).value();
  const double speckled = structuralSimilarity(base, noisy).value();
  EXPECT_GT(shifted, 0.98);
  EXPECT_LT(speckled, shifted - 0.05);
  EXPECT_FALSE(structuralSimilarity(Image(2, 2), Image(2, 3)).ok());
}

namespace {
void appendBe32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}
// A PNG chunk; the CRC is left zero (stb does not check it, and the padding's
// own CRC is checked separately below).
void appendChunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  appendBe32(out, std::uint32_t(data.size()));
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  appendBe32(out, 0);
}
// An 8-bit indexed PNG of one row per `rows` entry, its IDAT a stored (level 0)
// zlib stream, so the test needs no compressor.
std::vector<std::uint8_t> indexedPng(int width, const std::vector<std::vector<std::uint8_t>>& rows,
                                     const std::vector<std::uint8_t>& palette) {
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  appendBe32(ihdr, std::uint32_t(width));
  appendBe32(ihdr, std::uint32_t(rows.size()));
  ihdr.insert(ihdr.end(), {8, 3, 0, 0, 0});
  appendChunk(png, "IHDR", ihdr);
  appendChunk(png, "PLTE", palette);
  std::vector<std::uint8_t> raw;
  for (const auto& row : rows) {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), row.begin(), row.end());
  }
  std::vector<std::uint8_t> z = {0x78, 0x01, 0x01, std::uint8_t(raw.size()), std::uint8_t(raw.size() >> 8),
                                 std::uint8_t(~raw.size()), std::uint8_t(~raw.size() >> 8)};
  z.insert(z.end(), raw.begin(), raw.end());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  appendBe32(z, b << 16 | a);
  appendChunk(png, "IDAT", z);
  appendChunk(png, "IEND", {});
  return png;
}
}  // namespace

// The fuzzer's find: stb read indices past PLTE from uninitialised stack, so the
// same bytes gave different pixels from one decode to the next. Every palette
// length from 1 to 255 entries, with every index 0..255 present: indices inside
// the palette give its colour, those past it opaque black (libpng's answer).
TEST(Image, IndicesPastThePaletteAreBlackForEveryPaletteLength) {
  std::vector<std::vector<std::uint8_t>> rows(16, std::vector<std::uint8_t>(16));
  for (int i = 0; i < 256; ++i) rows[std::size_t(i / 16)][std::size_t(i % 16)] = std::uint8_t(i);
  for (int entries = 1; entries < 256; ++entries) {
    std::vector<std::uint8_t> palette;
    for (int e = 0; e < entries; ++e) palette.insert(palette.end(), {std::uint8_t(e), std::uint8_t(255 - e), 77});
    const auto png = indexedPng(16, rows, palette);
    auto image = decodePng(png, "indexed.png");
    ASSERT_TRUE(image.ok()) << image.error().message;
    for (int i = 0; i < 256; ++i) {
      const std::uint8_t* p = image->at(i % 16, i / 16);
      const bool inside = i < entries;
      ASSERT_EQ(p[0], inside ? i : 0) << entries << " entries, index " << i;
      ASSERT_EQ(p[1], inside ? 255 - i : 0) << entries << " entries, index " << i;
      ASSERT_EQ(p[2], inside ? 77 : 0) << entries << " entries, index " << i;
      ASSERT_EQ(p[3], 255) << entries << " entries, index " << i;
    }
  }
}

TEST(Image, PaddedPaletteIsAValidChunk) {
  const auto png = indexedPng(1, {{1}}, {10, 20, 30});
  const auto padded = pngWithFullPalette(png);
  // Signature, IHDR (25 bytes), then PLTE: length 768, "PLTE", 768 bytes, CRC.
  const std::size_t plte = 8 + 25;
  ASSERT_EQ(padded.size(), png.size() + 765);
  EXPECT_EQ((padded[plte] << 24 | padded[plte + 1] << 16 | padded[plte + 2] << 8 | padded[plte + 3]), 768);
  EXPECT_EQ(padded[plte + 8], 10);
  EXPECT_EQ(padded[plte + 8 + 3], 0);
  // The CRC of "PLTE" + 10 20 30 + 765 zero bytes, from Python's zlib.crc32.
  const std::size_t crc = plte + 8 + 768;
  EXPECT_EQ(std::uint32_t(padded[crc]) << 24 | std::uint32_t(padded[crc + 1]) << 16 |
                std::uint32_t(padded[crc + 2]) << 8 | padded[crc + 3],
            0x19ee4133u);
  // Already full, not indexed, or no PLTE before IDAT: nothing to pad.
  std::vector<std::uint8_t> full(768, 1);
  EXPECT_TRUE(pngWithFullPalette(indexedPng(1, {{1}}, full)).empty());
  EXPECT_TRUE(pngWithFullPalette(std::vector<std::uint8_t>(png.begin(), png.begin() + 20)).empty());
}
