// Environment images (core/linear_image.h): a Radiance .hdr or a PNG by content,
// decoded to linear RGB; every bad file is an error naming it, and no truncation of
// a run-length coded .hdr makes the decoder hang.
#include <gtest/gtest.h>

#include <fstream>

#include "../support/radiance_file.h"
#include "core/image.h"
#include "core/linear_image.h"

using namespace engine;
using engine::test::ScratchFolder;

namespace {

std::string errorOf(const std::filesystem::path& path) {
  auto image = readLinearImage(path.string());
  return image ? std::string("no error") : image.error().message;
}

std::vector<glm::vec3> ramp(int width, int height) {
  std::vector<glm::vec3> pixels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) pixels.emplace_back(0.25f * float(x % 4), 0.5f * float(y % 3), 3.0f);
  return pixels;
}

}  // namespace

// Both layouts stb reads: run-length scanlines (width 16) and flat pixels (width 5),
// with values that RGBE stores exactly.
TEST(LinearImage, HdrReadsBackExactlyInBothLayouts) {
  ScratchFolder folder;
  for (const glm::ivec2 size : {glm::ivec2(16, 3), glm::ivec2(5, 4)}) {
    const auto path = folder / ("ramp" + std::to_string(size.x) + ".hdr");
    const auto pixels = ramp(size.x, size.y);
    test::writeHdr(path, size.x, size.y, pixels);
    auto info = readHdrOrPngInfo(path.string());
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_EQ(info->format, ImageFormat::Hdr);
    EXPECT_EQ(glm::ivec2(info->width, info->height), size);
    auto image = readLinearImage(path.string());
    ASSERT_TRUE(image.ok()) << image.error().message;
    ASSERT_EQ(glm::ivec2(image->width, image->height), size);
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) EXPECT_EQ(image->at(x, y), pixels[std::size_t(y * size.x + x)]) << x << "," << y;
  }
}

// A PNG is sRGB: 128 reads as the sRGB curve's 0.2158605, not 128 / 255.
TEST(LinearImage, PngIsDecodedFromSrgb) {
  ScratchFolder folder;
  Image png(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      std::uint8_t* p = png.at(x, y);
      p[0] = 128, p[1] = std::uint8_t(255 * x / 2), p[2] = 10, p[3] = 7;  // alpha is dropped
    }
  const auto path = folder / "srgb.png";
  ASSERT_TRUE(writePng(path.string(), png).ok());
  auto image = readLinearImage(path.string());
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_NEAR(image->at(0, 0).r, 0.2158605f, 1e-6f);
  EXPECT_EQ(image->at(0, 1).g, 0.0f);
  EXPECT_EQ(image->at(2, 1).g, 1.0f);
  EXPECT_NEAR(image->at(1, 0).b, 10.0f / 255.0f / 12.92f, 1e-7f);  // the curve's linear toe
}

TEST(LinearImage, BadFilesAreErrorsNamingThem) {
  ScratchFolder folder;
  EXPECT_EQ(errorOf(folder / "missing.hdr"), (folder / "missing.hdr").string() + ": no such file");
  EXPECT_EQ(errorOf(folder.path()), folder.path().string() + ": not a regular file");
  test::writeBytes(folder / "empty.hdr", {});
  EXPECT_EQ(errorOf(folder / "empty.hdr"), (folder / "empty.hdr").string() + ": the file is empty (0 bytes)");
  // A name says nothing: text called .hdr, and a real PNG called .hdr, which is read.
  test::writeBytes(folder / "text.hdr", {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
  EXPECT_EQ(errorOf(folder / "text.hdr"), (folder / "text.hdr").string() + ": neither a Radiance .hdr nor a PNG image");
  ASSERT_TRUE(writePng((folder / "png.hdr").string(), Image(2, 2)).ok());
  EXPECT_EQ(errorOf(folder / "png.hdr"), "no error");
  const std::string zero = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n";
  test::writeBytes(folder / "zero.hdr", std::vector<std::uint8_t>(zero.begin(), zero.end()));
  EXPECT_EQ(errorOf(folder / "zero.hdr"), (folder / "zero.hdr").string() + ": image is 0x0 pixels; each side must be in [1, 16384]");
  const std::string negative = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y -3 +X 4\n";
  test::writeBytes(folder / "negative.hdr", std::vector<std::uint8_t>(negative.begin(), negative.end()));
  EXPECT_EQ(errorOf(folder / "negative.hdr"),
            (folder / "negative.hdr").string() + ": image is 4x-3 pixels; each side must be in [1, 16384]");
  const std::string big = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n";
  test::writeBytes(folder / "big.hdr", std::vector<std::uint8_t>(big.begin(), big.end()));
  EXPECT_EQ(errorOf(folder / "big.hdr"),
            (folder / "big.hdr").string() + ": image is 8192x8192 pixels, over the limit of 33554432 pixels");
}

// stb reads zeros past the end of the data and then loops forever on an empty run:
// every cut of a run-length file, and of a flat one, must be refused instead.
TEST(LinearImage, EveryTruncationOfAnHdrIsRefused) {
  ScratchFolder folder;
  for (const glm::ivec2 size : {glm::ivec2(16, 3), glm::ivec2(5, 4)}) {
    const auto whole = test::encodeHdr(size.x, size.y, ramp(size.x, size.y));
    const std::size_t header = test::encodeHdr(size.x, 0, {}).size();
    for (std::size_t length = header; length < whole.size(); ++length) {
      const auto path = folder / "cut.hdr";
      test::writeBytes(path, std::vector<std::uint8_t>(whole.begin(), whole.begin() + std::ptrdiff_t(length)));
      EXPECT_NE(errorOf(path).find("the Radiance data ends early"), std::string::npos) << "cut at " << length;
    }
  }
}

TEST(LinearImage, AnEmptyRunIsRefused) {
  ScratchFolder folder;
  auto bytes = test::encodeHdr(16, 1, ramp(16, 1));
  const std::size_t firstRun = bytes.size() - 4 * (1 + 16);  // the first channel's count byte
  ASSERT_EQ(bytes[firstRun], 16);
  bytes[firstRun] = 0;
  test::writeBytes(folder / "empty_run.hdr", bytes);
  EXPECT_EQ(errorOf(folder / "empty_run.hdr"),
            (folder / "empty_run.hdr").string() + ": cannot read image: bad run length in Radiance scanline 0");
}
