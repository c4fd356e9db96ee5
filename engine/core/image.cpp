#include "core/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

namespace engine {

void flipVertically(Image& image) {
  const size_t row = static_cast<size_t>(image.width) * 4;
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < image.height / 2; ++y) {
    std::uint8_t* top = image.at(0, y);
    std::uint8_t* bottom = image.at(0, image.height - 1 - y);
    std::copy(top, top + row, tmp.begin());
    std::copy(bottom, bottom + row, top);
    std::copy(tmp.begin(), tmp.end(), bottom);
  }
}

namespace {

std::uint32_t readBe32(std::span<const std::uint8_t> bytes, std::size_t at) {
  return std::uint32_t{bytes[at]} << 24 | std::uint32_t{bytes[at + 1]} << 16 | std::uint32_t{bytes[at + 2]} << 8 |
         std::uint32_t{bytes[at + 3]};
}

void appendBe32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

// PNG's CRC-32 (ISO 3309), over a chunk's type and data.
std::uint32_t pngCrc(std::span<const std::uint8_t> bytes) {
  static const std::array<std::uint32_t, 256> kTable = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::uint8_t b : bytes) c = kTable[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

}  // namespace

std::vector<std::uint8_t> pngWithFullPalette(std::span<const std::uint8_t> bytes) {
  constexpr std::size_t kFullPalette = 256 * 3;
  if (bytes.size() < 26 || bytes[25] != 3) return {};  // IHDR's colour type: 3 is indexed
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::size_t length = readBe32(bytes, at);
    if (at + 12 + length > bytes.size()) return {};
    const auto type = bytes.subspan(at + 4, 4);
    if (std::equal(type.begin(), type.end(), "IDAT") || std::equal(type.begin(), type.end(), "IEND")) return {};
    if (!std::equal(type.begin(), type.end(), "PLTE")) {
      at += 12 + length;
      continue;
    }
    // A length that is not whole entries, or over 256 of them, stb refuses itself.
    if (length % 3 != 0 || length >= kFullPalette) return {};
    std::vector<std::uint8_t> out(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(at));
    out.reserve(bytes.size() + kFullPalette - length);
    appendBe32(out, kFullPalette);
    const std::size_t chunkStart = out.size();
    out.insert(out.end(), type.begin(), type.end());
    const auto data = bytes.subspan(at + 8, length);
    out.insert(out.end(), data.begin(), data.end());
    out.resize(chunkStart + 4 + kFullPalette, 0);
    appendBe32(out, pngCrc(std::span(out).subspan(chunkStart)));
    out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at + 12 + length), bytes.end());
    return out;
  }
  return {};
}

std::span<const std::uint8_t> withFullPalette(std::span<const std::uint8_t> bytes,
                                              std::vector<std::uint8_t>& storage) {
  storage = pngWithFullPalette(bytes);
  return storage.empty() ? bytes : std::span<const std::uint8_t>(storage);
}

Status checkPngHeader(std::span<const std::uint8_t> bytes, const std::string& name) {
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
    return makeError(name + ": cannot read image: not a PNG file");
  if (bytes.size() > kMaxImageFileBytes)
    return makeError(name + ": cannot read image: " + std::to_string(bytes.size()) + " bytes, the limit is " +
                     std::to_string(kMaxImageFileBytes));
  // IHDR is the first chunk: length, "IHDR", width, height (big-endian).
  if (bytes.size() < 24 || !std::equal(bytes.begin() + 12, bytes.begin() + 16, "IHDR"))
    return makeError(name + ": cannot read image: PNG has no IHDR header");
  auto be32 = [&](std::size_t at) { return readBe32(bytes, at); };
  const std::uint64_t w = be32(16), h = be32(20);
  if (w == 0 || h == 0 || w > std::uint64_t(kMaxImageSide) || h > std::uint64_t(kMaxImageSide))
    return makeError(name + ": image is " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels; each side must be in [1, " + std::to_string(kMaxImageSide) + "]");
  if (w * h > kMaxImagePixels)
    return makeError(name + ": image is " + std::to_string(w) + "x" + std::to_string(h) + " pixels, over the limit of " +
                     std::to_string(kMaxImagePixels) + " pixels");
  // stb trusts chunk lengths and reserves memory for an IDAT's declared length
  // before reading it, so a 60-byte file could make it allocate gigabytes.
  for (std::size_t at = 8; at + 8 <= bytes.size();) {
    const std::uint64_t length = be32(at);
    const std::string type(bytes.begin() + static_cast<std::ptrdiff_t>(at) + 4,
                           bytes.begin() + static_cast<std::ptrdiff_t>(at) + 8);
    if (at + 12 + length > bytes.size())
      return makeError(name + ": cannot read image: PNG chunk at byte " + std::to_string(at) +
                       " declares " + std::to_string(length) + " bytes, past the end of the file");
    if (type == "IEND") break;
    at += static_cast<std::size_t>(12 + length);
  }
  // The least data any PNG of this size holds: one filter byte and one bit per
  // pixel per row.
  const std::uint64_t leastRaw = h * (1 + (w + 7) / 8);
  if (leastRaw > (std::uint64_t(bytes.size()) + 1) * 1032)
    return makeError(name + ": image claims " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels, more than its " + std::to_string(bytes.size()) + " bytes can hold");
  return Ok{};
}

Result<Image> decodePng(std::span<const std::uint8_t> bytes, const std::string& name) {
  if (Status s = checkPngHeader(bytes, name); !s) return s.error();
  std::vector<std::uint8_t> padded;
  const auto png = withFullPalette(bytes, padded);
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 4);
  if (!data) return makeError(name + ": cannot read image: " + stbi_failure_reason());
  Image image(w, h);
  std::copy(data, data + static_cast<size_t>(w) * h * 4, image.pixels.begin());
  stbi_image_free(data);
  return image;
}

namespace {
std::atomic<std::uint64_t> gImageFilesRead{0};
}  // namespace

std::uint64_t imageFilesRead() { return gImageFilesRead.load(); }
void countImageFileRead() { gImageFilesRead.fetch_add(1); }

Result<Image> readPng(const std::string& path) {
  countImageFileRead();
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(path + ": cannot read image: " + ec.message());
  if (size > kMaxImageFileBytes)
    return makeError(path + ": cannot read image: " + std::to_string(size) + " bytes, the limit is " +
                     std::to_string(kMaxImageFileBytes));
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes(static_cast<size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    return makeError(path + ": cannot read image: cannot read the file");
  return decodePng(bytes, path);
}

Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes, const std::string& format) {
  const std::string tmp = path + ".tmp";
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  out.close();  // a failed open, write or close leaves the stream failed
  if (!out) {
    std::remove(tmp.c_str());
    return makeError(path + ": cannot write " + format + " (is the folder there and writable?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    return makeError(path + ": cannot write " + format + ": " + ec.message());
  }
  return Ok{};
}

Status writePng(const std::string& path, const Image& image) {
  if (image.empty()) return makeError(path + ": refusing to write an empty image");
  // stbi_write_png encodes to memory and writes that: the same bytes come here.
  std::vector<std::uint8_t> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    out->insert(out->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 4, image.pixels.data(), image.width * 4))
    return makeError(path + ": cannot encode PNG");
  return writeFileAtomically(path, encoded, "PNG");
}

Result<ImageDiff> compareImages(const Image& a, const Image& b, int threshold, const PixelMask* mask) {
  if (a.width != b.width || a.height != b.height) {
    return makeError("images differ in size: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                     std::to_string(b.height));
  }
  if (auto s = checkMaskSize(mask, a.width, a.height); !s) return s.error();
  ImageDiff d;
  d.threshold = threshold;
  double sumAbs = 0.0, sumSq = 0.0;
  size_t over = 0;
  const size_t pixels = static_cast<size_t>(a.width) * a.height;
  const size_t count = mask ? mask->count : pixels;
  for (size_t i = 0; i < pixels; ++i) {
    if (!counts(mask, i)) continue;
    int pixelMax = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
      pixelMax = std::max(pixelMax, diff);
      sumAbs += diff;
      sumSq += double(diff) * diff;
    }
    d.maxAbs = std::max(d.maxAbs, pixelMax);
    if (pixelMax > threshold) ++over;
  }
  const double n = double(count) * 3.0;
  d.meanAbs = count ? sumAbs / n : 0.0;
  d.shareOver = count ? double(over) / double(count) : 0.0;
  const double mse = count ? sumSq / n : 0.0;
  d.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                      : 10.0 * std::log10(255.0 * 255.0 / mse);
  return d;
}

namespace {

// The separable 11-tap Gaussian of SSIM, edges clamped.
std::vector<double> gaussianBlur(const std::vector<double>& in, int w, int h) {
  static const std::array<double, 11> kernel = [] {
    std::array<double, 11> k{};
    double sum = 0.0;
    for (int i = 0; i < 11; ++i) sum += k[size_t(i)] = std::exp(-double((i - 5) * (i - 5)) / (2.0 * 1.5 * 1.5));
    for (double& v : k) v /= sum;
    return k;
  }();
  std::vector<double> tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int i = -5; i <= 5; ++i) s += kernel[size_t(i + 5)] * in[size_t(y) * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))];
      tmp[size_t(y) * size_t(w) + size_t(x)] = s;
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int i = -5; i <= 5; ++i) s += kernel[size_t(i + 5)] * tmp[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w) + size_t(x)];
      out[size_t(y) * size_t(w) + size_t(x)] = s;
    }
  }
  return out;
}

std::vector<double> luma(const Image& image) {
  std::vector<double> y(size_t(image.width) * size_t(image.height));
  for (size_t i = 0; i < y.size(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    y[i] = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  }
  return y;
}

}  // namespace

Result<double> structuralSimilarity(const Image& a, const Image& b, const PixelMask* mask) {
  if (a.width != b.width || a.height != b.height) return makeError("images differ in size");
  if (a.empty()) return makeError("empty images");
  if (auto s = checkMaskSize(mask, a.width, a.height); !s) return s.error();
  const int w = a.width, h = a.height;
  const std::vector<double> x = luma(a), y = luma(b);
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  const auto mx = gaussianBlur(x, w, h), my = gaussianBlur(y, w, h);
  const auto sxx = gaussianBlur(xx, w, h), syy = gaussianBlur(yy, w, h), sxy = gaussianBlur(xy, w, h);
  constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  double sum = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!counts(mask, i)) continue;
    const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
    sum += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return sum / double(mask ? mask->count : x.size());
}

Result<PixelMask> maskFromImage(const Image& image, int width, int height, const std::string& name) {
  if (image.width != width || image.height != height)
    return makeError(name + ": the mask is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels, the images " + std::to_string(width) + "x" + std::to_string(height));
  PixelMask mask;
  mask.width = width;
  mask.height = height;
  mask.selected.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t i = 0; i < mask.selected.size(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    mask.selected[i] = (p[0] | p[1] | p[2]) != 0;
    mask.count += mask.selected[i];
  }
  if (mask.count == 0) return makeError(name + ": the mask selects no pixel (every pixel is black)");
  return mask;
}

Image diffImage(const Image& a, const Image& b) {
  Image out(std::min(a.width, b.width), std::min(a.height, b.height));
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int diff = std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
        out.at(x, y)[c] = static_cast<std::uint8_t>(std::min(255, diff * 4));
      }
      out.at(x, y)[3] = 255;
    }
  }
  return out;
}

}  // namespace engine
