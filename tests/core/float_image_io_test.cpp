// Float images in files (core/float_image_io.h): OpenEXR and PFM give back exactly
// the floats written, extremes included; PFM's layout is the standard one; every
// broken file is an error naming it, never a crash or a hang.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>

#include "../support/files.h"
#include "../support/radiance_file.h"
#include "core/float_image_io.h"

using namespace engine;
using engine::test::ScratchFolder;

namespace {

// Random values over many magnitudes, and the extremes a renderer can produce: zeros
// of both signs, a denormal, float's least normal, half's largest (6e4) and far past
// it, infinity.
FloatImage extremeImage(int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> mantissa(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-40, 38);
  FloatImage image;
  image.width = width;
  image.height = height;
  for (int i = 0; i < width * height * 3; ++i) image.rgb.push_back(mantissa(rng) * std::pow(10.0f, float(exponent(rng))));
  const float extremes[] = {0.0f, -0.0f, 1e-40f, std::numeric_limits<float>::min(), 6e4f, 65504.0f, 1e30f,
                            std::numeric_limits<float>::infinity()};
  for (std::size_t i = 0; i < std::size(extremes) && i * 2 < image.rgb.size(); ++i) image.rgb[i * 2] = extremes[i];
  return image;
}

// Equal to the bit: -0 is not 0, and what a float file keeps is its bits.
void expectSameBits(const FloatImage& read, const FloatImage& written) {
  ASSERT_EQ(read.width, written.width);
  ASSERT_EQ(read.height, written.height);
  ASSERT_EQ(read.rgb.size(), written.rgb.size());
  for (std::size_t i = 0; i < written.rgb.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(read.rgb[i]), std::bit_cast<std::uint32_t>(written.rgb[i]))
        << "value " << i << ": read " << read.rgb[i] << ", wrote " << written.rgb[i];
  }
}

std::string readError(const std::filesystem::path& path) {
  auto image = readFloatImage(path.string());
  return image ? std::string("no error") : image.error().message;
}

// A new file each time: truncating one in place makes ext4 flush it on close
// (auto_da_alloc), which took 7 s over the cuts below on a busy disk.
void writeNewFile(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::filesystem::remove(path);
  test::writeBytes(path, bytes);
}

std::vector<std::uint8_t> pfmText(const std::string& text) { return {text.begin(), text.end()}; }

void appendFloats(std::vector<std::uint8_t>& out, std::initializer_list<float> values, bool bigEndian) {
  for (float v : values) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(bits >> (8 * (bigEndian ? 3 - k : k))));
  }
}

}  // namespace

TEST(FloatImageIo, BothFormatsGiveBackExactlyTheFloatsWritten) {
  ScratchFolder folder;
  // 1x1, odd sizes, and one of many of OpenEXR's 16-row ZIP blocks.
  for (const auto& [width, height] : std::vector<std::pair<int, int>>{{1, 1}, {7, 5}, {97, 61}}) {
    const FloatImage image = extremeImage(width, height, std::uint32_t(width * 31 + height));
    for (const char* name : {"image.pfm", "image.exr", "IMAGE.EXR"}) {
      SCOPED_TRACE(std::string(name) + " " + std::to_string(width) + "x" + std::to_string(height));
      const auto path = folder / name;
      const Status written = writeFloatImage(path.string(), image);
      ASSERT_TRUE(written.ok()) << written.error().message;
      EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
      EXPECT_EQ(floatFormatOfFile(path.string()), floatFormatForName(path.string()));
      auto read = readFloatImage(path.string());
      ASSERT_TRUE(read.ok()) << read.error().message;
      expectSameBits(*read, image);
    }
  }
}

// "PF", the size, scale -1 (little-endian), then RGB floats from the bottom row up.
TEST(FloatImageIo, PfmIsTheStandardLayout) {
  ScratchFolder folder;
  FloatImage image;
  image.width = 1;
  image.height = 2;
  image.rgb = {1.0f, 2.0f, 3.0f,   // top
               4.0f, 5.0f, 6.0f};  // bottom
  ASSERT_TRUE(writeFloatImage((folder / "layout.pfm").string(), image).ok());
  std::vector<std::uint8_t> expected = pfmText("PF\n1 2\n-1.0\n");
  appendFloats(expected, {4.0f, 5.0f, 6.0f, 1.0f, 2.0f, 3.0f}, false);
  const auto bytes = test::readBytes(folder / "layout.pfm");
  EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), expected);
}

// A positive scale is big-endian, and its magnitude multiplies the values (as pbrt
// reads PFM); any whitespace separates the header's fields.
TEST(FloatImageIo, PfmReadsEitherByteOrderAndItsScale) {
  ScratchFolder folder;
  std::vector<std::uint8_t> bytes = pfmText("PF\n1  1\r\n2.0\n");
  appendFloats(bytes, {1.0f, 0.5f, -3.0f}, true);
  test::writeBytes(folder / "big.pfm", bytes);
  auto image = readFloatImage((folder / "big.pfm").string());
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_EQ(image->at(0, 0), glm::vec3(2.0f, 1.0f, -6.0f));
}

TEST(FloatImageIo, NamesAndContentsPickTheFormat) {
  EXPECT_EQ(floatFormatForName("out/a.exr"), FloatFormat::Exr);
  EXPECT_EQ(floatFormatForName("A.Pfm"), FloatFormat::Pfm);
  EXPECT_EQ(floatFormatForName("a.png"), std::nullopt);
  EXPECT_EQ(floatFormatForName("exr"), std::nullopt);
  EXPECT_EQ(lowerCaseExtension("dir.x/a.PNG"), ".png");
  ScratchFolder folder;
  // Content wins over the name, and a missing file has none.
  ASSERT_TRUE(writeFloatImage((folder / "a.pfm").string(), extremeImage(2, 2, 1)).ok());
  std::filesystem::rename(folder / "a.pfm", folder / "a.exr");
  EXPECT_EQ(floatFormatOfFile((folder / "a.exr").string()), FloatFormat::Pfm);
  EXPECT_TRUE(readFloatImage((folder / "a.exr").string()).ok());
  EXPECT_EQ(floatFormatOfFile((folder / "none.exr").string()), std::nullopt);
  EXPECT_TRUE(isFloatImageFile((folder / "none.exr").string()));
  EXPECT_FALSE(isFloatImageFile((folder / "none.png").string()));
}

TEST(FloatImageIo, BadPfmFilesAreErrorsNamingThem) {
  ScratchFolder folder;
  std::vector<std::uint8_t> pixels;
  appendFloats(pixels, {1, 2, 3, 4, 5, 6}, false);
  const auto pfm = [&](const std::string& header, std::size_t pixelBytes) {
    std::vector<std::uint8_t> bytes = pfmText(header);
    bytes.insert(bytes.end(), pixels.begin(), pixels.begin() + std::ptrdiff_t(std::min(pixelBytes, pixels.size())));
    while (bytes.size() < header.size() + pixelBytes) bytes.push_back(0);
    return bytes;
  };
  const struct {
    const char* name;
    std::vector<std::uint8_t> bytes;
    const char* message;
  } cases[] = {
      {"empty.pfm", {}, "the file is empty (0 bytes)"},
      {"magic.pfm", pfm("P6\n1 2\n255\n", 24), "neither an OpenEXR nor a PFM image"},
      {"grey.pfm", pfm("Pf\n1 2\n-1.0\n", 8), "cannot read PFM: greyscale PFM (Pf) is not read, only colour (PF)"},
      {"truncated.pfm", pfm("PF\n1 2\n-1.0\n", 23), "cannot read PFM: 23 bytes of pixels, 1x2 RGB needs 24 (truncated)"},
      {"long.pfm", pfm("PF\n1 2\n-1.0\n", 28), "cannot read PFM: 28 bytes of pixels, 1x2 RGB needs 24"},
      {"header_only.pfm", pfmText("PF\n1 2\n"), "cannot read PFM: the header ends early or is malformed"},
      {"size.pfm", pfm("PF\n1 x\n-1.0\n", 24), "cannot read PFM: the size \"1 x\" is not two numbers"},
      {"scale.pfm", pfm("PF\n1 2\n0\n", 24), "cannot read PFM: the scale \"0\" is not a non-zero number"},
      {"nan_scale.pfm", pfm("PF\n1 2\nnan\n", 24), "cannot read PFM: the scale \"nan\" is not a non-zero number"},
      {"zero.pfm", pfm("PF\n0 2\n-1.0\n", 0), "image is 0x2 pixels; each side must be in [1, 16384]"},
      {"negative.pfm", pfm("PF\n-1 2\n-1.0\n", 0), "image is -1x2 pixels; each side must be in [1, 16384]"},
      {"huge.pfm", pfm("PF\n16384 16384\n-1.0\n", 24), "image is 16384x16384 pixels, over the limit of 33554432 pixels"},
      {"overflow.pfm", pfm("PF\n99999999999999999999 2\n-1.0\n", 24), "is not two numbers"},
  };
  for (const auto& c : cases) {
    const auto path = folder / c.name;
    test::writeBytes(path, c.bytes);
    const std::string error = readError(path);
    EXPECT_NE(error.find(path.string() + ": "), std::string::npos) << error;
    EXPECT_NE(error.find(c.message), std::string::npos) << c.name << ": " << error;
  }
  EXPECT_EQ(readError(folder / "missing.pfm"), (folder / "missing.pfm").string() + ": no such file");
}

// Every cut of an OpenEXR file, and every byte of it turned over, is refused or read
// (a changed pixel is still a picture), with tinyexr's reason on one line: never a
// crash, a hang or a read past the end (the sanitizer build checks the last).
TEST(FloatImageIo, EveryCutOrCorruptedOpenExrIsAnErrorOrAnImage) {
  ScratchFolder folder;
  const auto good = folder / "good.exr";
  ASSERT_TRUE(writeFloatImage(good.string(), extremeImage(5, 18, 7)).ok());
  const auto bytes = test::readBytes(good);
  const auto path = folder / "bad.exr";
  for (std::size_t size = 1; size < bytes.size(); ++size) {
    writeNewFile(path, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(size)));
    const std::string error = readError(path);
    ASSERT_EQ(error.rfind(path.string() + ": ", 0), 0u) << "cut at " << size << ": " << error;
    ASSERT_EQ(error.find('\n'), std::string::npos) << error;
  }
  int refused = 0;
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::vector<std::uint8_t> changed(bytes.begin(), bytes.end());
    changed[at] ^= 0xFF;
    writeNewFile(path, changed);
    auto image = readFloatImage(path.string());
    if (!image) {
      ++refused;
      ASSERT_EQ(image.error().message.rfind(path.string() + ": ", 0), 0u) << image.error().message;
    } else {
      ASSERT_EQ(image->rgb.size(), std::size_t(5 * 18 * 3)) << "byte " << at;
    }
  }
  EXPECT_GT(refused, 0);
  test::writeBytes(path, std::vector<std::uint8_t>{0x76, 0x2f, 0x31, 0x01});
  EXPECT_EQ(readError(path).rfind(path.string() + ": cannot read OpenEXR: ", 0), 0u) << readError(path);
}

// Nothing is left behind where a file cannot be written, and the name picks the format.
TEST(FloatImageIo, WritingFailsCleanly) {
  ScratchFolder folder;
  const FloatImage image = extremeImage(3, 2, 3);
  const std::string missing = (folder / "no/such/folder/a.exr").string();
  const Status unwritable = writeFloatImage(missing, image);
  ASSERT_FALSE(unwritable.ok());
  EXPECT_EQ(unwritable.error().message, missing + ": cannot write OpenEXR (is the folder there and writable?)");
  const Status badName = writeFloatImage((folder / "a.tif").string(), image);
  ASSERT_FALSE(badName.ok());
  EXPECT_NE(badName.error().message.find("must end in .exr or .pfm"), std::string::npos);
  EXPECT_FALSE(writeFloatImage((folder / "empty.pfm").string(), FloatImage{}).ok());
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}
