#pragma once
// Radiance .hdr files for tests, written by hand (the format is a text header and
// RGBE pixels), so a test controls every byte: the run-length layout stb decodes for
// widths in [8, 32768), or flat pixels for narrower images. Values m / 256 * 2^e
// (0.75, 0.5, 0.25, 3.0, ...) survive the round trip exactly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace engine::test {

// Shared exponent encoding as Greg Ward's (and stb_image_write's) writer does it.
inline std::array<std::uint8_t, 4> rgbe(const glm::vec3& c) {
  const float largest = std::max({c.r, c.g, c.b});
  if (largest < 1e-32f) return {0, 0, 0, 0};
  int exponent = 0;
  const float scale = std::frexp(largest, &exponent) * 256.0f / largest;
  return {std::uint8_t(c.r * scale), std::uint8_t(c.g * scale), std::uint8_t(c.b * scale), std::uint8_t(exponent + 128)};
}

// `pixels`: width * height, top row first.
inline std::vector<std::uint8_t> encodeHdr(int width, int height, const std::vector<glm::vec3>& pixels) {
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
                             std::to_string(width) + "\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  const bool runLength = width >= 8 && width < 32768;
  for (int y = 0; y < height; ++y) {
    std::vector<std::array<std::uint8_t, 4>> row;
    for (int x = 0; x < width; ++x) row.push_back(rgbe(pixels[std::size_t(y * width + x)]));
    if (!runLength) {
      for (const auto& p : row) out.insert(out.end(), p.begin(), p.end());
      continue;
    }
    // A scanline mark, then each channel as literal runs of at most 128 bytes.
    out.insert(out.end(), {2, 2, std::uint8_t(width >> 8), std::uint8_t(width & 0xFF)});
    for (int channel = 0; channel < 4; ++channel) {
      for (int x = 0; x < width; x += 128) {
        const int count = std::min(128, width - x);
        out.push_back(std::uint8_t(count));
        for (int i = 0; i < count; ++i) out.push_back(row[std::size_t(x + i)][std::size_t(channel)]);
      }
    }
  }
  return out;
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

inline void writeHdr(const std::filesystem::path& path, int width, int height, const std::vector<glm::vec3>& pixels) {
  writeBytes(path, encodeHdr(width, height, pixels));
}

// A folder of the running test's own (ctest runs tests in parallel), made empty and
// removed when the test ends.
class ScratchFolder {
 public:
  ScratchFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = std::filesystem::temp_directory_path() / ("engine_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace engine::test
