#pragma once
// Linear RGB images in float, rows top to bottom: what an environment's lat-long
// map is made of. Read from a Radiance .hdr (linear already) or a PNG (sRGB, decoded
// to linear), told apart by their content, never by the file's name.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"

namespace engine {

struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // width * height * 3, linear, top row first

  glm::vec3 at(int x, int y) const {
    const float* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
  bool empty() const { return width == 0 || height == 0; }
};

// An environment image costs 12 bytes a pixel as float RGB (and a GPU copy), so its
// limit is below core/image.h's: 8192 x 4096, the largest lat-long maps in common use.
inline constexpr std::uint64_t kMaxLinearImagePixels = 1ull << 25;

enum class ImageFormat { Hdr, Png };

struct ImageInfo {
  ImageFormat format = ImageFormat::Png;
  int width = 0;
  int height = 0;
};

// The checks every linear image reader makes before decoding (here and in
// core/float_image_io.h). checkImageFile: the file is there, a regular file, not
// empty and within kMaxImageFileBytes. checkLinearImageSize: each side in
// [1, kMaxImageSide] and at most kMaxLinearImagePixels. Errors name the file.
Status checkImageFile(const std::string& path);
Status checkLinearImageSize(const std::string& path, long long width, long long height);
// The whole file (after checkImageFile).
Result<std::vector<std::uint8_t>> readImageBytes(const std::string& path);

// What the file is, from its header alone (nothing is decoded): a Radiance .hdr or a
// PNG whose size is at least 1 x 1 and within the limits. Errors name the file: no
// such file, an empty file, neither format, 0 pixels, too large.
Result<ImageInfo> readHdrOrPngInfo(const std::string& path);

// The whole image in linear RGB: a .hdr as stored, a PNG decoded from sRGB (its alpha
// is dropped). A .hdr's run-length data is checked to be complete before stb decodes
// it: stb reads zeros past the end of a truncated file and then never finishes a
// scanline.
Result<FloatImage> readLinearImage(const std::string& path);

// The sRGB transfer function (IEC 61966-2-1), encoded [0, 1] to linear, as GL decodes
// SRGB8 texels.
inline float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace engine
