// imgdiff A B: compares two images and exits 1 when over a limit, 2 on bad input.
// Two PNGs: max and mean absolute difference over RGB, PSNR, share of pixels over a
// threshold, SSIM, and with --flip the mean LDR-FLIP. Two linear images (Radiance
// .hdr, OpenEXR, PFM, in any pair): max and mean absolute difference and PSNR over
// the linear values, and with --flip the mean HDR-FLIP, the figure that reads light
// beyond [0, 1] as a viewer would. --mask restricts every figure to the pixels a
// mask image selects.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/flip.h"
#include "core/float_image_io.h"
#include "core/image.h"
#include "core/linear_image.h"
#include "core/pixel_mask.h"

namespace {

using namespace engine;

struct Options {
  std::string a, b, diffPath, flipMapPath, maskPath;
  std::optional<double> maxMean, minPsnr, maxFlip;
  std::optional<int> maxAbs;
  int threshold = 8;
  bool flip = false;
  float ppd = kFlipDefaultPpd;
  ToneMapper toneMapper = ToneMapper::Aces;

  bool wantsFlip() const { return flip || maxFlip || !flipMapPath.empty(); }
};

int fail(const std::string& message) {
  std::fprintf(stderr, "imgdiff: %s\n", message.c_str());
  return 2;
}

// Linear light: an OpenEXR or PFM file (by content, else by name), or a Radiance
// .hdr (by content).
bool isLinear(const std::string& path) {
  if (isFloatImageFile(path)) return true;
  auto info = readHdrOrPngInfo(path);
  return info && info->format == ImageFormat::Hdr;
}

Result<FloatImage> readLinear(const std::string& path) {
  return isFloatImageFile(path) ? readFloatImage(path) : readLinearImage(path);
}

struct LinearDiff {
  double maxAbs = 0.0, meanAbs = 0.0, psnr = 0.0;
};

// Over the linear RGB values of the pixels counted. The PSNR's peak is the
// reference's (A's) brightest channel there, 1 where A is black: an HDR image has
// no white to measure against, and its own peak keeps the figure independent of the
// images' scale.
LinearDiff compareLinear(const FloatImage& a, const FloatImage& b, const PixelMask* mask) {
  LinearDiff d;
  double sumAbs = 0.0, sumSquares = 0.0, peak = 0.0;
  std::size_t channels = 0;
  for (std::size_t i = 0; i < std::size_t(a.width) * std::size_t(a.height); ++i) {
    if (!counts(mask, i)) continue;
    for (std::size_t c = i * 3; c < i * 3 + 3; ++c) {
      // Equal values differ by 0, infinities too (inf - inf is NaN).
      const double diff = a.rgb[c] == b.rgb[c] ? 0.0 : std::abs(double(a.rgb[c]) - double(b.rgb[c]));
      d.maxAbs = std::max(d.maxAbs, diff);
      sumAbs += diff;
      sumSquares += diff * diff;
      peak = std::max(peak, double(a.rgb[c]));
    }
    channels += 3;
  }
  const double mse = channels ? sumSquares / double(channels) : 0.0;
  d.meanAbs = channels ? sumAbs / double(channels) : 0.0;
  if (peak <= 0.0) peak = 1.0;
  d.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(peak * peak / mse);
  return d;
}

// The mask of --mask for images of this size, or none.
Result<std::optional<PixelMask>> readMask(const Options& o, int width, int height) {
  if (o.maskPath.empty()) return std::optional<PixelMask>();
  auto image = readPng(o.maskPath);
  if (!image) return image.error();
  auto mask = maskFromImage(*image, width, height, o.maskPath);
  if (!mask) return mask.error();
  return std::optional<PixelMask>(std::move(*mask));
}

std::string maskText(const std::optional<PixelMask>& mask) {
  return mask ? " mask_pixels " + std::to_string(mask->count) : "";
}

// Writes the map of --flip-map, if asked.
Status writeFlipMap(const Options& o, const FlipMap& map) {
  if (o.flipMapPath.empty()) return Ok{};
  return writePng(o.flipMapPath, flipMapImage(map));
}

std::string sizeMismatch(const Options& o, int width, int height, int otherWidth, int otherHeight) {
  return "images differ in size: " + o.a + " is " + std::to_string(width) + "x" + std::to_string(height) + ", " +
         o.b + " " + std::to_string(otherWidth) + "x" + std::to_string(otherHeight);
}

// The two images, of one size, and the mask for that size: what every comparison
// starts from. `read` is readPng or readLinear.
template <typename Picture>
struct Inputs {
  Picture a, b;
  std::optional<PixelMask> mask;
  const PixelMask* maskOrNull() const { return mask ? &*mask : nullptr; }
};

template <typename Picture>
Result<Inputs<Picture>> readInputs(const Options& o, Result<Picture> (*read)(const std::string&)) {
  auto a = read(o.a);
  if (!a) return a.error();
  auto b = read(o.b);
  if (!b) return b.error();
  if (a->width != b->width || a->height != b->height)
    return makeError(sizeMismatch(o, a->width, a->height, b->width, b->height));
  auto mask = readMask(o, a->width, a->height);
  if (!mask) return mask.error();
  return Inputs<Picture>{std::move(*a), std::move(*b), std::move(*mask)};
}

int comparePngs(const Options& o) {
  auto in = readInputs<Image>(o, readPng);
  if (!in) return fail(in.error().message);
  const Image &imageA = in->a, &imageB = in->b;
  const PixelMask* m = in->maskOrNull();
  auto d = compareImages(imageA, imageB, o.threshold, m);
  if (!d) return fail(d.error().message);
  auto ssim = structuralSimilarity(imageA, imageB, m);
  if (!ssim) return fail(ssim.error().message);
  std::optional<FlipMap> flipMap;
  std::optional<double> flipMeanValue;
  if (o.wantsFlip()) {
    auto map = ldrFlip(imageA, imageB, o.ppd);
    if (!map) return fail(map.error().message);
    auto mean = flipMean(*map, m);
    if (!mean) return fail(mean.error().message);
    flipMap = std::move(*map);
    flipMeanValue = *mean;
  }
  const std::string flipText = flipMeanValue ? " flip " + std::to_string(*flipMeanValue) : "";
  std::printf("max_abs %d mean_abs %.4f psnr %.2f over_%d %.4f%% ssim %.4f%s%s\n", d->maxAbs, d->meanAbs, d->psnr,
              o.threshold, d->shareOver * 100.0, *ssim, flipText.c_str(), maskText(in->mask).c_str());
  if (!o.diffPath.empty()) {
    if (auto s = writePng(o.diffPath, diffImage(imageA, imageB)); !s) return fail(s.error().message);
  }
  if (flipMap) {
    if (auto s = writeFlipMap(o, *flipMap); !s) return fail(s.error().message);
  }
  bool over = false;
  if (o.maxMean && d->meanAbs > *o.maxMean) over = true;
  if (o.maxAbs && d->maxAbs > *o.maxAbs) over = true;
  if (o.minPsnr && d->psnr < *o.minPsnr) over = true;
  if (o.maxFlip && *flipMeanValue > *o.maxFlip) over = true;
  if (over) std::printf("over the limit\n");
  return over ? 1 : 0;
}

struct HdrFlipFigure {
  double mean = 0.0;
  ExposureRange exposures;
};

// The pair's mean HDR-FLIP over the pixels counted, its map written when asked.
Result<HdrFlipFigure> meanHdrFlip(const Options& o, const Inputs<FloatImage>& in) {
  HdrFlipOptions options;
  options.ppd = o.ppd;
  options.toneMapper = o.toneMapper;
  auto result = hdrFlip(in.a, in.b, options);
  if (!result) return result.error();
  auto mean = flipMean(result->map, in.maskOrNull());
  if (!mean) return mean.error();
  if (auto s = writeFlipMap(o, result->map); !s) return s.error();
  return HdrFlipFigure{*mean, result->exposures};
}

// Two linear images: their values' differences and PSNR, and HDR-FLIP with --flip
// (the 8-bit figures and the difference image would clip what makes them HDR).
int compareRadiance(const Options& o) {
  if (!o.diffPath.empty() || o.maxMean || o.maxAbs)
    return fail("--diff, --max-mean and --max-abs are for PNG images, not linear ones (.hdr, .exr, .pfm)");
  auto in = readInputs<FloatImage>(o, readLinear);
  if (!in) return fail(in.error().message);
  const LinearDiff d = compareLinear(in->a, in->b, in->maskOrNull());
  std::optional<HdrFlipFigure> flip;
  if (o.wantsFlip()) {
    auto figure = meanHdrFlip(o, *in);
    if (!figure) return fail(figure.error().message);
    flip = *figure;
  }
  std::printf("max_abs %.6g mean_abs %.6g psnr %.2f", d.maxAbs, d.meanAbs, d.psnr);
  if (flip) {
    const ExposureRange& e = flip->exposures;
    std::printf(" hdr_flip %.6f exposures %.4f %.4f %d", flip->mean, e.start, e.stop, e.count);
  }
  std::printf("%s\n", maskText(in->mask).c_str());
  const bool over = (o.minPsnr && d.psnr < *o.minPsnr) || (flip && o.maxFlip && flip->mean > *o.maxFlip);
  if (over) std::printf("over the limit\n");
  return over ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Compare two images (PNGs, or linear images: Radiance .hdr, OpenEXR, PFM); exit 1 when a limit is "
               "exceeded, 2 on bad input.",
               "imgdiff"};
  Options o;
  app.add_option("A", o.a, "First image (the reference, for FLIP)")->required();
  app.add_option("B", o.b, "Second image")->required();
  app.add_option("--max-mean", o.maxMean, "Largest mean absolute difference allowed (0..255)");
  app.add_option("--max-abs", o.maxAbs, "Largest single channel difference allowed (0..255)");
  app.add_option("--min-psnr", o.minPsnr, "Smallest PSNR allowed, dB (linear images: over their values, the "
                                         "reference's brightest channel the peak)");
  app.add_option("--threshold", o.threshold, "Channel difference counted as 'over'")->capture_default_str();
  app.add_option("--diff", o.diffPath, "Write a difference image (x4 gain) here");
  app.add_flag("--flip", o.flip,
               "Also print the mean FLIP (LDR-FLIP of PNGs, HDR-FLIP of linear images), in [0, 1], 0 when equal");
  app.add_option("--flip-map", o.flipMapPath, "Write FLIP's per-pixel error here as a grey PNG (implies --flip)");
  app.add_option("--max-flip", o.maxFlip, "Largest mean FLIP allowed (implies --flip)");
  app.add_option("--ppd", o.ppd, "FLIP's pixels per degree of the viewer (default 67.02: 0.7 m from a 0.7 m wide "
                                 "3840-pixel monitor)")
      ->check(CLI::Range(0.01f, 1000.0f));
  std::string toneMapper = "aces";
  app.add_option("--tone-mapper", toneMapper, "HDR-FLIP's tone map")
      ->check(CLI::IsMember({"aces", "reinhard", "hable"}))
      ->capture_default_str();
  app.add_option("--mask", o.maskPath,
                 "Count only the pixels where this PNG (same size) is not black, in every figure; FLIP's filters "
                 "still see the neighbours");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "imgdiff: %s (see --help)\n", e.what());
    return 2;
  }
  o.toneMapper = toneMapper == "reinhard" ? ToneMapper::Reinhard
                 : toneMapper == "hable"  ? ToneMapper::Hable
                                          : ToneMapper::Aces;
  const bool linearA = isLinear(o.a), linearB = isLinear(o.b);
  if (linearA != linearB) {
    // A file that cannot be read is the error to report, not the pair's mismatch.
    const std::string &linear = linearA ? o.a : o.b, &other = linearA ? o.b : o.a;
    if (auto image = readLinear(linear); !image) return fail(image.error().message);
    if (auto info = readHdrOrPngInfo(other); !info) return fail(info.error().message);
    return fail(linear + " is a linear image and " + other +
                " is not; compare two PNGs or two linear images (.hdr, .exr, .pfm)");
  }
  return linearA ? compareRadiance(o) : comparePngs(o);
}
