#include "core/linear_image.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <span>

#include "core/image.h"

namespace engine {
namespace {

bool hasPngSignature(const std::string& path) {
  static const char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1A', '\n'};
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  return in.read(head, 8) && std::equal(head, head + 8, kSignature);
}

// Where a Radiance file's pixels begin: after the header's blank line and the
// resolution line ("-Y height +X width", the only layout stb reads).
Result<std::size_t> hdrDataStart(std::span<const std::uint8_t> bytes, const std::string& path) {
  const auto newline = [&](std::size_t from) {
    return std::size_t(std::find(bytes.begin() + std::ptrdiff_t(from), bytes.end(), '\n') - bytes.begin());
  };
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t end = newline(at);
    if (end >= bytes.size()) break;
    if (end == at) {  // the blank line; the resolution line follows
      const std::size_t resolutionEnd = newline(end + 1);
      if (resolutionEnd >= bytes.size()) break;
      return resolutionEnd + 1;
    }
    at = end + 1;
  }
  return makeError(path + ": cannot read image: the Radiance header does not end");
}

// Walks a Radiance file's scanlines as stb_image's decoder reads them (flat pixels
// for widths outside [8, 32768), else per scanline a 4-byte mark and four
// run-length coded channels; a scanline without the mark makes stb read the whole
// image as flat pixels from there) and refuses data that ends early or holds an
// empty run, on which stb would loop forever.
Status checkHdrData(std::span<const std::uint8_t> bytes, std::size_t at, int width, int height,
                    const std::string& path) {
  const Error truncated = makeError(path + ": cannot read image: the Radiance data ends early");
  const auto flatFits = [&](std::size_t from) {
    return bytes.size() - from >= std::uint64_t(width) * std::uint64_t(height) * 4;
  };
  if (width < 8 || width >= 32768) return flatFits(at) ? Status(Ok{}) : Status(truncated);
  for (int row = 0; row < height; ++row) {
    if (bytes.size() - at < 4) return truncated;
    if (bytes[at] != 2 || bytes[at + 1] != 2 || (bytes[at + 2] & 0x80)) return flatFits(at) ? Status(Ok{}) : Status(truncated);
    if ((bytes[at + 2] << 8 | bytes[at + 3]) != width)
      return makeError(path + ": cannot read image: Radiance scanline " + std::to_string(row) + " is not " +
                       std::to_string(width) + " pixels long");
    at += 4;
    for (int channel = 0; channel < 4; ++channel) {
      for (int x = 0; x < width;) {
        if (at >= bytes.size()) return truncated;
        const int count = bytes[at] > 128 ? bytes[at] - 128 : bytes[at];
        const std::size_t stored = bytes[at] > 128 ? 1 : std::size_t(count);
        if (count == 0 || count > width - x)
          return makeError(path + ": cannot read image: bad run length in Radiance scanline " + std::to_string(row));
        if (bytes.size() - at - 1 < stored) return truncated;
        at += 1 + stored;
        x += count;
      }
    }
  }
  return Ok{};
}

Result<FloatImage> decodeHdr(const std::string& path, const ImageInfo& info) {
  auto bytes = readImageBytes(path);
  if (!bytes) return bytes.error();
  auto start = hdrDataStart(*bytes, path);
  if (!start) return start.error();
  if (auto s = checkHdrData(*bytes, *start, info.width, info.height, path); !s) return s.error();
  int w = 0, h = 0, channels = 0;
  float* data = stbi_loadf_from_memory(bytes->data(), int(bytes->size()), &w, &h, &channels, 3);
  if (!data) return makeError(path + ": cannot read image: " + stbi_failure_reason());
  FloatImage image;
  image.width = w;
  image.height = h;
  image.rgb.assign(data, data + static_cast<size_t>(w) * h * 3);
  stbi_image_free(data);
  return image;
}

Result<FloatImage> decodePngToLinear(const std::string& path) {
  auto png = readPng(path);
  if (!png) return png.error();
  static const std::array<float, 256> kDecode = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  FloatImage image;
  image.width = png->width;
  image.height = png->height;
  image.rgb.resize(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t i = 0, n = static_cast<size_t>(image.width) * image.height; i < n; ++i) {
    for (size_t c = 0; c < 3; ++c) image.rgb[i * 3 + c] = kDecode[png->pixels[i * 4 + c]];
  }
  return image;
}

}  // namespace

Status checkLinearImageSize(const std::string& path, long long width, long long height) {
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
    return makeError(path + ": image is " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels; each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
  if (std::uint64_t(width) * std::uint64_t(height) > kMaxLinearImagePixels)
    return makeError(path + ": image is " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels, over the limit of " + std::to_string(kMaxLinearImagePixels) + " pixels");
  return Ok{};
}

Result<std::vector<std::uint8_t>> readImageBytes(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(path + ": cannot read image: " + ec.message());
  std::vector<std::uint8_t> bytes(static_cast<size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    return makeError(path + ": cannot read image: cannot read the file");
  return bytes;
}

Status checkImageFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return makeError(path + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec)) return makeError(path + ": not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(path + ": cannot read image: " + ec.message());
  if (size == 0) return makeError(path + ": the file is empty (0 bytes)");
  if (size > kMaxImageFileBytes)
    return makeError(path + ": cannot read image: " + std::to_string(size) + " bytes, the limit is " +
                     std::to_string(kMaxImageFileBytes));
  return Ok{};
}

Result<ImageInfo> readHdrOrPngInfo(const std::string& path) {
  if (auto s = checkImageFile(path); !s) return s.error();
  ImageInfo info;
  int channels = 0;
  if (stbi_is_hdr(path.c_str())) {
    info.format = ImageFormat::Hdr;
    // stb reads the size from the header; it takes 0 or negative sides as they are.
    if (!stbi_info(path.c_str(), &info.width, &info.height, &channels))
      return makeError(path + ": cannot read image: " + stbi_failure_reason());
  } else if (hasPngSignature(path)) {
    info.format = ImageFormat::Png;
    // The PNG checks of core/image.h (a 0x0 size, chunks past the end, a claimed size
    // the file cannot hold), before stb looks at it.
    auto bytes = readImageBytes(path);
    if (!bytes) return bytes.error();
    if (auto s = checkPngHeader(*bytes, path); !s) return s.error();
    if (!stbi_info_from_memory(bytes->data(), int(bytes->size()), &info.width, &info.height, &channels))
      return makeError(path + ": cannot read image: " + stbi_failure_reason());
  } else {
    return makeError(path + ": neither a Radiance .hdr nor a PNG image");
  }
  if (auto s = checkLinearImageSize(path, info.width, info.height); !s) return s.error();
  return info;
}

Result<FloatImage> readLinearImage(const std::string& path) {
  auto info = readHdrOrPngInfo(path);
  if (!info) return info.error();
  if (info->format != ImageFormat::Hdr) return decodePngToLinear(path);  // readPng counts the read
  countImageFileRead();
  return decodeHdr(path, *info);
}

}  // namespace engine
