// Images: tinygltf's loader keeps them encoded after checking their size, all of
// them are decoded at once after parsing, and Converter makes them RGBA8.
#include <algorithm>
#include <cstring>
#include <span>

#include <tbb/parallel_for.h>

#include "asset/gltf_loader_impl.h"
#include "core/image.h"

namespace engine::gltf_loader {
namespace {

std::uint32_t bigEndian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

// Width and height from a PNG or JPEG header, or {0, 0} when not found. Read
// before decoding so that a tiny file claiming 60000 x 60000 pixels is refused
// instead of allocating gigabytes.
std::pair<std::uint32_t, std::uint32_t> imageSize(const unsigned char* bytes, std::size_t size) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size >= 24 && std::memcmp(bytes, kPng, 8) == 0) return {bigEndian(bytes + 16, 4), bigEndian(bytes + 20, 4)};
  if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return {0, 0};
  std::size_t at = 2;
  while (at + 9 < size && bytes[at] == 0xFF) {
    unsigned char marker = bytes[at + 1];
    bool startOfFrame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (startOfFrame) return {bigEndian(bytes + at + 7, 2), bigEndian(bytes + at + 5, 2)};
    at += 2 + bigEndian(bytes + at + 2, 2);
  }
  return {0, 0};
}

}  // namespace

// Decoding failures only warn: a model without its texture is still worth showing.
bool tolerantImageLoader(tinygltf::Image* image, const int imageIndex, std::string* err,
                         std::string* warn, int reqWidth, int reqHeight,
                         const unsigned char* bytes, int size, void*) {
  const std::size_t length = size > 0 ? static_cast<std::size_t>(size) : 0;
  const std::string name = "image " + std::to_string(imageIndex);
  auto refuse = [&](const std::string& why) {
    if (warn) *warn += name + ": " + why + "\n";
    image->image.clear();
    return true;
  };
  // glTF allows PNG and JPEG only. stb would also try TGA (which has no magic),
  // PSD, HDR, ... and could take any corrupted bytes for one of them, with a size
  // that nothing here has checked.
  const bool png = length >= 8 && bytes[0] == 0x89 && bytes[1] == 'P';
  const bool jpeg = length >= 4 && bytes[0] == 0xFF && bytes[1] == 0xD8;
  if (!png && !jpeg) return refuse("not a PNG or JPEG file");
  auto [width, height] = imageSize(bytes, length);
  // The same limits as readPng (core/image.h).
  if (width > static_cast<std::uint32_t>(kMaxImageSide) || height > static_cast<std::uint32_t>(kMaxImageSide))
    return refuse(std::to_string(width) + " x " + std::to_string(height) + " pixels is over the limit of " +
                  std::to_string(kMaxImageSide));
  if (std::uint64_t{width} * height > kMaxImagePixels)
    return refuse(std::to_string(width) + " x " + std::to_string(height) + " pixels is over the limit of " +
                  std::to_string(kMaxImagePixels) + " pixels");
  if (jpeg && (width == 0 || height == 0)) return refuse("JPEG without a frame header");
  if (png) {
    if (Status s = checkPngHeader(std::span(bytes, length), name); !s) {
      if (warn) *warn += s.error().message + "\n";
      image->image.clear();
      return true;
    }
  }
  std::vector<std::uint8_t> padded;
  const auto checked = png ? withFullPalette(std::span(bytes, length), padded) : std::span(bytes, length);
  // Decoded after parsing, every image at once (decodeImages): kept encoded here.
  image->image.assign(checked.begin(), checked.end());
  image->as_is = true;
  (void)err;
  (void)reqWidth;
  (void)reqHeight;
  return true;
}

// The images tolerantImageLoader kept encoded, decoded in parallel (stb decodes one
// image on one thread: DamagedHelmet's five 2048^2 textures took 0.3 s one after the
// other); a failure warns as the loader does, in the images' order.
void decodeImages(tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings) {
  std::vector<std::string> failures(model.images.size());
  tbb::parallel_for(std::size_t(0), model.images.size(), [&](std::size_t i) {
    tinygltf::Image& image = model.images[i];
    if (!image.as_is || image.image.empty()) return;
    tinygltf::Image decoded;
    std::string error, warn;
    const bool ok = tinygltf::LoadImageData(&decoded, static_cast<int>(i), &error, &warn, 0, 0, image.image.data(),
                                            static_cast<int>(image.image.size()), nullptr);
    if (ok) {
      image.width = decoded.width;
      image.height = decoded.height;
      image.component = decoded.component;
      image.bits = decoded.bits;
      image.pixel_type = decoded.pixel_type;
      image.image = std::move(decoded.image);
    } else {
      image.image.clear();
      failures[i] = "image " + std::to_string(i) + ": cannot decode: " + error;
    }
    image.as_is = false;
  });
  for (const std::string& failure : failures)
    if (!failure.empty()) warnings.push_back(path + ": " + failure);
}

Status Converter::convertImages() {
  for (std::size_t i = 0; i < gltf_.images.size(); ++i) {
    const tinygltf::Image& src = gltf_.images[i];
    ImageData image;
    image.name = src.name;
    if (src.uri.rfind("data:", 0) != 0) image.uri = src.uri;
    if (!toRgba8(src, image.image)) {
      warn("image " + str(i) + " (" + (src.uri.empty() ? src.name : src.uri) +
           "): missing or undecodable, using a white 1x1 fallback");
      image.missing = true;
      image.image = Image(1, 1);
      std::fill(image.image.pixels.begin(), image.image.pixels.end(), std::uint8_t{255});
    }
    out_.images.push_back(std::move(image));
  }
  return Ok{};
}

bool Converter::toRgba8(const tinygltf::Image& src, Image& dst) {
  if (src.width <= 0 || src.height <= 0 || src.component < 1 || src.component > 4) return false;
  std::size_t pixels = static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height);
  std::size_t bytesPerChannel = src.bits == 16 ? 2 : 1;
  if (src.bits != 8 && src.bits != 16) return false;
  if (src.image.size() < pixels * static_cast<std::size_t>(src.component) * bytesPerChannel) return false;
  dst = Image(src.width, src.height);
  if (src.component == 4 && bytesPerChannel == 1) {  // what tinygltf decodes to: as it is
    std::memcpy(dst.pixels.data(), src.image.data(), pixels * 4);
    return true;
  }
  for (std::size_t p = 0; p < pixels; ++p) {
    std::uint8_t rgba[4] = {0, 0, 0, 255};
    for (int c = 0; c < src.component; ++c) {
      std::size_t at = (p * static_cast<std::size_t>(src.component) + static_cast<std::size_t>(c)) * bytesPerChannel;
      // 16-bit samples are little-endian as stb returns them; keep the high byte.
      rgba[c] = bytesPerChannel == 2 ? src.image[at + 1] : src.image[at];
    }
    // Grey and grey+alpha images spread the grey over RGB.
    if (src.component <= 2) {
      std::uint8_t alpha = src.component == 2 ? rgba[1] : std::uint8_t{255};
      rgba[1] = rgba[2] = rgba[0];
      rgba[3] = alpha;
    }
    std::memcpy(&dst.pixels[p * 4], rgba, 4);
  }
  return true;
}

}  // namespace engine::gltf_loader
