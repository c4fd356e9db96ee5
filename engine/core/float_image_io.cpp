#include "core/float_image_io.h"

#include <tinyexr.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <vector>

#include "core/image.h"

namespace engine {
namespace {

constexpr std::array<std::uint8_t, 4> kExrMagic = {0x76, 0x2f, 0x31, 0x01};

bool isPfmHead(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f') && std::isspace(bytes[2]);
}

std::size_t pixelCount(const FloatImage& image) { return std::size_t(image.width) * std::size_t(image.height); }

// ---- PFM: "PF\n<width> <height>\n<scale>\n", then rows of RGB floats, bottom row
// first; a negative scale means little-endian, its magnitude multiplies the values.

void appendFloat(std::vector<std::uint8_t>& out, float value) {
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int shift = 0; shift < 32; shift += 8) out.push_back(std::uint8_t(bits >> shift));
}

float floatAt(std::span<const std::uint8_t> bytes, std::size_t at, bool bigEndian) {
  std::uint32_t bits = 0;
  for (int k = 0; k < 4; ++k) bits |= std::uint32_t(bytes[at + std::size_t(bigEndian ? 3 - k : k)]) << (8 * k);
  return std::bit_cast<float>(bits);
}

std::vector<std::uint8_t> encodePfm(const FloatImage& image) {
  const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.reserve(out.size() + pixelCount(image) * 12);
  const std::size_t row = std::size_t(image.width) * 3;
  for (int y = image.height - 1; y >= 0; --y) {
    for (std::size_t i = std::size_t(y) * row; i < std::size_t(y + 1) * row; ++i) appendFloat(out, image.rgb[i]);
  }
  return out;
}

// The header's three fields (width, height, scale), each after whitespace; `at` ends
// past the one whitespace byte after the scale, where the pixels start.
Result<std::array<std::string, 3>> pfmFields(std::span<const std::uint8_t> bytes, std::size_t& at,
                                              const std::string& path) {
  std::array<std::string, 3> fields;
  for (std::string& field : fields) {
    while (at < bytes.size() && std::isspace(bytes[at])) ++at;
    while (at < bytes.size() && !std::isspace(bytes[at]) && field.size() < 32) field += char(bytes[at++]);
    if (at >= bytes.size() || !std::isspace(bytes[at]))
      return makeError(path + ": cannot read PFM: the header ends early or is malformed");
  }
  ++at;
  return fields;
}

template <typename T>
bool parseWhole(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end;
}

Result<FloatImage> decodePfm(std::span<const std::uint8_t> bytes, const std::string& path) {
  if (bytes[1] == 'f') return makeError(path + ": cannot read PFM: greyscale PFM (Pf) is not read, only colour (PF)");
  std::size_t at = 2;
  auto fields = pfmFields(bytes, at, path);
  if (!fields) return fields.error();
  long long width = 0, height = 0;
  double scale = 0.0;
  if (!parseWhole((*fields)[0], width) || !parseWhole((*fields)[1], height))
    return makeError(path + ": cannot read PFM: the size \"" + (*fields)[0] + " " + (*fields)[1] + "\" is not two numbers");
  if (!parseWhole((*fields)[2], scale) || !std::isfinite(scale) || scale == 0.0)
    return makeError(path + ": cannot read PFM: the scale \"" + (*fields)[2] + "\" is not a non-zero number");
  if (auto s = checkLinearImageSize(path, width, height); !s) return s.error();
  const std::uint64_t expected = std::uint64_t(width) * std::uint64_t(height) * 12, stored = bytes.size() - at;
  if (stored != expected)
    return makeError(path + ": cannot read PFM: " + std::to_string(stored) + " bytes of pixels, " +
                     std::to_string(width) + "x" + std::to_string(height) + " RGB needs " + std::to_string(expected) +
                     (stored < expected ? " (truncated)" : ""));
  FloatImage image;
  image.width = int(width);
  image.height = int(height);
  image.rgb.resize(pixelCount(image) * 3);
  const float factor = float(std::abs(scale));
  const std::size_t row = std::size_t(width) * 3;
  for (std::size_t y = 0; y < std::size_t(height); ++y) {
    const std::size_t from = at + (std::size_t(height) - 1 - y) * row * 4;  // the file's bottom row first
    for (std::size_t i = 0; i < row; ++i) {
      const float value = floatAt(bytes, from + i * 4, scale > 0.0);
      image.rgb[y * row + i] = factor == 1.0f ? value : value * factor;
    }
  }
  return image;
}

// ---- OpenEXR through tinyexr, whose C structures are freed however a read ends.

template <typename T, void (*kInit)(T*), int (*kFree)(T*)>
struct Owned {
  T value;
  Owned() { kInit(&value); }
  ~Owned() { kFree(&value); }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
};
using ExrHeader = Owned<EXRHeader, InitEXRHeader, FreeEXRHeader>;
using ExrImage = Owned<EXRImage, InitEXRImage, FreeEXRImage>;

// tinyexr's message (freed here) on one line, or `what` when it gave none.
Error exrError(const std::string& path, const char* action, const char* what, const char* message) {
  std::string text = message ? message : what;
  if (message) FreeEXRErrorMessage(message);
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return makeError(path + ": cannot " + action + " OpenEXR: " + text);
}

// Float32, not half: the path tracer's values stay exact (half keeps 11 bits and
// overflows above 65504) and a file read back equals what was written. ZIP is
// lossless. Channels in B, G, R order, as EXR viewers expect.
Result<std::vector<std::uint8_t>> encodeExr(const FloatImage& image, const std::string& path) {
  std::array<std::vector<float>, 3> planes;  // B, G, R
  for (int c = 0; c < 3; ++c) {
    planes[std::size_t(c)].resize(pixelCount(image));
    for (std::size_t i = 0; i < pixelCount(image); ++i) planes[std::size_t(c)][i] = image.rgb[i * 3 + std::size_t(2 - c)];
  }
  std::array<EXRChannelInfo, 3> channels{};
  std::array<int, 3> types{TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
  std::array<int, 3> stored = types;
  std::array<unsigned char*, 3> data{};
  for (std::size_t c = 0; c < 3; ++c) {
    channels[c].name[0] = "BGR"[c];
    data[c] = reinterpret_cast<unsigned char*>(planes[c].data());
  }
  EXRHeader header;
  InitEXRHeader(&header);  // owns nothing: the arrays below are ours
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_channels = 3;
  header.channels = channels.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = stored.data();
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = 3;
  exr.width = image.width;
  exr.height = image.height;
  exr.images = data.data();
  unsigned char* memory = nullptr;
  const char* message = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &message);
  if (size == 0) return exrError(path, "write", "the encoder failed", message);
  std::vector<std::uint8_t> bytes(memory, memory + size);
  std::free(memory);
  return bytes;
}

// The index of each of R, G and B among the header's channels, asking tinyexr for
// float where a channel is stored as half; an error for what this reader refuses.
Result<std::array<int, 3>> rgbChannels(EXRHeader& header, const std::string& path) {
  static constexpr const char* kRgb = "RGB";
  std::array<int, 3> index{-1, -1, -1};
  for (int c = 0; c < header.num_channels; ++c) {
    const EXRChannelInfo& channel = header.channels[c];
    const char* at = std::strchr(kRgb, channel.name[0]);
    if (channel.name[0] == '\0' || channel.name[1] != '\0' || !at) continue;
    if (channel.x_sampling != 1 || channel.y_sampling != 1)
      return makeError(path + ": cannot read OpenEXR: channel " + channel.name + " is subsampled");
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT)
      return makeError(path + ": cannot read OpenEXR: channel " + channel.name + " holds integers, not half or float");
    header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    index[std::size_t(at - kRgb)] = c;
  }
  if (std::count(index.begin(), index.end(), -1) > 0)
    return makeError(path + ": cannot read OpenEXR: it has no R, G and B channels");
  return index;
}

Result<FloatImage> decodeExr(std::span<const std::uint8_t> bytes, const std::string& path) {
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
    return makeError(path + ": cannot read OpenEXR: bad version field");
  if (version.multipart || version.non_image || version.tiled)
    return makeError(path + ": cannot read OpenEXR: only single-part scanline images are read (not tiled, multi-part or deep)");
  ExrHeader parsed;
  const char* message = nullptr;
  if (ParseEXRHeaderFromMemory(&parsed.value, &version, bytes.data(), bytes.size(), &message) != TINYEXR_SUCCESS)
    return exrError(path, "read", "bad header", message);
  const EXRBox2i& window = parsed.value.data_window;
  const long long width = static_cast<long long>(window.max_x) - window.min_x + 1;
  const long long height = static_cast<long long>(window.max_y) - window.min_y + 1;
  if (auto s = checkLinearImageSize(path, width, height); !s) return s.error();
  auto index = rgbChannels(parsed.value, path);
  if (!index) return index.error();
  ExrImage loaded;
  if (LoadEXRImageFromMemory(&loaded.value, &parsed.value, bytes.data(), bytes.size(), &message) != TINYEXR_SUCCESS) {
    // tinyexr 1.0.1 frees a failed load's channel array itself and leaves the
    // pointer behind: forget it, or the owner would free it again (a double free,
    // found by the test that cuts a file at every byte). The channels in that array
    // it leaks (tests/sanitizers/lsan.supp says why); nothing here can reach them.
    InitEXRImage(&loaded.value);
    return exrError(path, "read", "bad pixel data", message);
  }
  if (!loaded.value.images || loaded.value.width != width || loaded.value.height != height)
    return makeError(path + ": cannot read OpenEXR: the pixels do not fill the data window");
  FloatImage image;
  image.width = int(width);
  image.height = int(height);
  image.rgb.resize(pixelCount(image) * 3);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto* plane = reinterpret_cast<const float*>(loaded.value.images[(*index)[k]]);
    for (std::size_t i = 0; i < pixelCount(image); ++i) image.rgb[i * 3 + k] = plane[i];
  }
  return image;
}

std::optional<FloatFormat> formatOfBytes(std::span<const std::uint8_t> bytes) {
  if (bytes.size() >= kExrMagic.size() && std::equal(kExrMagic.begin(), kExrMagic.end(), bytes.begin()))
    return FloatFormat::Exr;
  if (isPfmHead(bytes)) return FloatFormat::Pfm;
  return std::nullopt;
}

}  // namespace

std::string lowerCaseExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension;
}

std::optional<FloatFormat> floatFormatForName(const std::string& path) {
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".exr") return FloatFormat::Exr;
  if (extension == ".pfm") return FloatFormat::Pfm;
  return std::nullopt;
}

std::optional<FloatFormat> floatFormatOfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<std::uint8_t, 4> head{};
  in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
  return formatOfBytes(std::span(head.data(), std::size_t(std::max<std::streamsize>(in.gcount(), 0))));
}

bool isFloatImageFile(const std::string& path) {
  return floatFormatOfFile(path).has_value() || floatFormatForName(path).has_value();
}

Status writeFloatImage(const std::string& path, const FloatImage& image) {
  const auto format = floatFormatForName(path);
  if (!format) return makeError(path + ": a float image's name must end in .exr or .pfm");
  if (image.empty() || image.rgb.size() != pixelCount(image) * 3)
    return makeError(path + ": refusing to write an empty image");
  if (*format == FloatFormat::Pfm) return writeFileAtomically(path, encodePfm(image), "PFM");
  auto bytes = encodeExr(image, path);
  if (!bytes) return bytes.error();
  return writeFileAtomically(path, *bytes, "OpenEXR");
}

Result<FloatImage> readFloatImage(const std::string& path) {
  if (auto s = checkImageFile(path); !s) return s.error();
  auto bytes = readImageBytes(path);
  if (!bytes) return bytes.error();
  const auto format = formatOfBytes(*bytes);
  if (!format) return makeError(path + ": neither an OpenEXR nor a PFM image");
  return *format == FloatFormat::Exr ? decodeExr(*bytes, path) : decodePfm(*bytes, path);
}

}  // namespace engine
