#pragma once
// 8-bit RGBA images in memory, PNG read/write (stb) and image comparison. Rows are
// stored top to bottom, as PNG stores them.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/pixel_mask.h"
#include "core/result.h"

namespace engine {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4, RGBA, top row first

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h * 4, 0) {}
  std::uint8_t* at(int x, int y) { return &pixels[(static_cast<size_t>(y) * width + x) * 4]; }
  const std::uint8_t* at(int x, int y) const {
    return &pixels[(static_cast<size_t>(y) * width + x) * 4];
  }
  bool empty() const { return width == 0 || height == 0; }
};

// Reverses the row order (GL reads bottom row first).
void flipVertically(Image& image);

// Texel index i wrapped into [0, n), negative indices too (a repeating texture's
// and a lat-long image's columns).
inline int wrapTexel(int i, int n) {
  // Most indices are in range already (a bilinear tap's neighbour leaves it only at
  // an edge): no division for them, on the ray tracer's every texture read.
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) return i;
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// Limits on untrusted images, checked from the header before any pixel is
// decoded, so that a small file cannot claim gigabytes.
inline constexpr std::uint64_t kMaxImageFileBytes = 256ull * 1024 * 1024;
inline constexpr int kMaxImageSide = 16384;
// 8192 x 8192: 256 MiB as RGBA8, which the decoder holds twice at its peak.
inline constexpr std::uint64_t kMaxImagePixels = 1ull << 26;

// PNG only (stb would also decode a dozen other formats; a file named .png that is
// something else is refused rather than handed to those decoders). Errors name the
// file; a 0x0 or over-limit image is an error.
Result<Image> readPng(const std::string& path);
// Image files read so far by this process (readPng and readLinearImage): the scene
// layer decodes a scene's images once, and tests count that nothing reads them again.
std::uint64_t imageFilesRead();
void countImageFileRead();
// The same decoder on bytes in memory; `name` stands for the file in messages.
Result<Image> decodePng(std::span<const std::uint8_t> bytes, const std::string& name);
// Reads only the PNG header: refuses a 0x0 or over-limit size, and a size whose
// pixel data could not fit in the file even at zlib's best ratio (1032:1), which a
// real PNG cannot have but a decompression bomb does; stb would allocate the whole
// image before finding out.
Status checkPngHeader(std::span<const std::uint8_t> bytes, const std::string& name);
// stb expands an indexed PNG through a 256-entry table that it fills only as far
// as PLTE goes, so an index past the palette read whatever its stack held and the
// same bytes decoded to different pixels. The PNG spec calls such an index an
// error; libpng draws it black. This returns the file with PLTE padded to 256
// black entries (CRC recomputed), which gives stb libpng's answer; empty when the
// file needs no padding. Every stb decode of untrusted PNG bytes goes through it.
std::vector<std::uint8_t> pngWithFullPalette(std::span<const std::uint8_t> bytes);
// `bytes`, or the padded copy held in `storage` when one is needed.
std::span<const std::uint8_t> withFullPalette(std::span<const std::uint8_t> bytes,
                                              std::vector<std::uint8_t>& storage);
// Writes to a temporary file beside `path` and renames it, so a failure never
// leaves a half-written PNG behind.
Status writePng(const std::string& path, const Image& image);
// The same for any encoded image: `bytes` into a temporary beside `path`, renamed
// over it once complete. Errors name the file and `format` ("PNG", "OpenEXR").
Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes, const std::string& format);

// Comparison over the RGB channels (alpha is ignored: it carries no picture).
struct ImageDiff {
  int maxAbs = 0;             // largest channel difference, 0..255
  double meanAbs = 0.0;       // mean channel difference, 0..255
  double psnr = 0.0;          // dB; +infinity when identical
  double shareOver = 0.0;     // share of pixels with some channel over `threshold`
  int threshold = 0;
};

// With a mask, every figure is over the pixels it selects alone.
Result<ImageDiff> compareImages(const Image& a, const Image& b, int threshold = 8,
                                const PixelMask* mask = nullptr);
// The structural similarity of the two images' luma (Wang et al. 2004: an 11 x 11
// Gaussian window of sigma 1.5, K1 = 0.01, K2 = 0.03, L = 255), the mean over the
// image: 1 for equal images, lower as structure differs. The trade table's
// perceptual column: PSNR weighs a bright noisy pixel like a lost edge, SSIM does not.
// With a mask, the mean over the pixels it selects (each window still sees its
// neighbours outside the mask).
Result<double> structuralSimilarity(const Image& a, const Image& b, const PixelMask* mask = nullptr);
// The mask of an image: a pixel is selected where any of its RGB channels is
// non-zero (alpha is ignored, as in every comparison). Errors name `name`: a size
// other than width x height, a mask that selects no pixel (every figure would be
// 0 / 0).
Result<PixelMask> maskFromImage(const Image& image, int width, int height, const std::string& name);
// A visual diff: black where equal, brighter where different (x4 gain).
Image diffImage(const Image& a, const Image& b);

}  // namespace engine
