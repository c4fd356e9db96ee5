#pragma once
// FLIP, the difference a viewer sees when two images alternate (Andersson et al.,
// "FLIP: A Difference Evaluator for Alternating Images", HPG 2020), and HDR-FLIP, its
// extension to high dynamic range (Andersson et al., "Visualizing Errors in Rendered
// High Dynamic Range Images", Eurographics 2021). Written here from the papers, with
// the constants and the separated filters of NVIDIA's reference implementation
// (github NVlabs/flip), whose figures it reproduces (docs/measuring.md#flip).
//
// Each pixel's error is in [0, 1]: a colour difference after the eye's contrast
// sensitivity has blurred both images (what is too fine to see at this viewing
// distance does not count), raised to a power that an edge or a point present in one
// image and not the other brings toward 0, so such features count in full. The mean
// is the one-number summary the authors recommend.
#include <optional>
#include <vector>

#include "core/image.h"
#include "core/linear_image.h"
#include "core/pixel_mask.h"
#include "core/result.h"

namespace engine {

// Pixels per degree of visual angle for a viewer `distance` metres from a monitor
// `monitorWidth` metres wide that shows `monitorPixels` pixels across.
constexpr float flipPixelsPerDegree(float distance, float monitorPixels, float monitorWidth) {
  return distance * (monitorPixels / monitorWidth) * (3.14159265358979f / 180.0f);
}
// FLIP's default viewer: 0.7 m from a 0.7 m wide monitor 3840 pixels across, about
// 67 pixels per degree (67.02).
inline constexpr float kFlipDefaultPpd = flipPixelsPerDegree(0.7f, 3840.0f, 0.7f);

struct FlipMap {
  int width = 0;
  int height = 0;
  std::vector<float> error;  // width * height, each in [0, 1], top row first
};

// LDR-FLIP of two linear RGB images, reference first (values are clamped to [0, 1]).
// An error when the sizes differ or the images are empty.
Result<FlipMap> ldrFlip(const FloatImage& reference, const FloatImage& test, float ppd = kFlipDefaultPpd);
// The same of two 8-bit sRGB images (alpha ignored), decoded to linear as
// NVIDIA's tool decodes a PNG.
Result<FlipMap> ldrFlip(const Image& reference, const Image& test, float ppd = kFlipDefaultPpd);
// An 8-bit sRGB image in linear float (alpha dropped).
FloatImage linearFromSrgb(const Image& image);

// The tone maps HDR-FLIP shows an exposure through. ACES is the paper's default
// (Narkowicz's fit with its 0.6 pre-exposure undone); Hable is Uncharted 2's curve.
enum class ToneMapper { Aces, Reinhard, Hable };

// The exposures (log2 of the multiplier) HDR-FLIP looks through, evenly spaced.
struct ExposureRange {
  float start = 0.0f;
  float stop = 0.0f;
  int count = 2;
  float at(int i) const { return count < 2 ? start : start + float(i) * ((stop - start) / float(count - 1)); }
};
// The paper's range for a reference image: from the exposure that tone maps its
// brightest pixel to 0.85 to the one that does so to its median luminance, one
// exposure per stop (at least 2). An image that is black (or whose median is black)
// falls back to its smallest non-zero luminance, then to exposure 0.
ExposureRange flipExposureRange(const FloatImage& reference, ToneMapper toneMapper = ToneMapper::Aces);
// The image times 2^exposure, tone mapped and clamped to [0, 1]: what one exposure
// of HDR-FLIP compares.
FloatImage flipToneMapped(const FloatImage& image, float exposure, ToneMapper toneMapper);

struct HdrFlipOptions {
  float ppd = kFlipDefaultPpd;
  ToneMapper toneMapper = ToneMapper::Aces;
  std::optional<ExposureRange> exposures;  // the reference's range when absent
};
struct HdrFlip {
  FlipMap map;  // each pixel's largest LDR-FLIP over the exposures
  ExposureRange exposures;
};
// HDR-FLIP of two linear RGB images of any range, reference first. Errors as
// ldrFlip's, and an exposure range that is not finite, backwards or of fewer than
// 2 exposures.
Result<HdrFlip> hdrFlip(const FloatImage& reference, const FloatImage& test, const HdrFlipOptions& options = {});

// The map's mean over the pixels the mask selects (all without one), in double.
// An error when the mask's size is not the map's or it selects nothing.
Result<double> flipMean(const FlipMap& map, const PixelMask* mask = nullptr);
// The map as a grey picture: round(255 * error) in each channel.
Image flipMapImage(const FlipMap& map);

}  // namespace engine
