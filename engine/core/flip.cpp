// LDR-FLIP: the colour pipeline (section 4 of the HPG 2020 paper) and the feature
// pipeline (section 5), with the spatial filters separated as NVIDIA's reference
// implementation separates them, so that a 1080p image takes a second, not minutes.
// Every step is in float, in the reference's order of operations, so that the means
// agree to the printed digits rather than merely to the metric's meaning.
#include "core/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace engine {
namespace {

// The paper's constants (HPG 2020, tables 1 and 2).
constexpr float kPi = 3.14159265358979f;
constexpr float kPiSquared = kPi * kPi;
constexpr float kColourExponent = 0.7f;    // q_c: HyAB distances are raised to it
constexpr float kCompressedShare = 0.4f;   // p_c: distances below p_c * cmax ...
constexpr float kCompressedTo = 0.95f;     // p_t: ... fill [0, p_t], the rest (p_t, 1]
constexpr float kFeatureWidth = 0.082f;    // g_w: the feature detectors' width, degrees
constexpr float kFeatureExponent = 0.5f;   // q_f: feature differences are raised to it

// The contrast sensitivity of each opponent channel is a Gaussian in the spatial
// domain, a * sqrt(pi / b) * exp(-pi^2 x^2 / b) with x in degrees (paper, eq. 2);
// the blue-yellow channel's is the sum of two.
struct Csf {
  float a, b;
};
constexpr Csf kAchromatic{1.0f, 0.0047f};
constexpr Csf kRedGreen{1.0f, 0.0053f};
constexpr Csf kBlueYellow1{34.1f, 0.04f};
constexpr Csf kBlueYellow2{13.5f, 0.025f};
constexpr float kWidestB = 0.04f;

// D65 white in XYZ for the sRGB matrix below, and its reciprocal.
constexpr std::array<float, 3> kWhite{0.950428545f, 1.0f, 1.088900371f};
constexpr std::array<float, 3> kInverseWhite{1.052156925f, 1.0f, 0.918357670f};

// A pixel in one of the colour spaces below: linear RGB, XYZ, YCxCz or L*a*b*.
struct Colour {
  float x, y, z;
};

// Clamped to [0, 1]; NaN gives 0 (the reference's clamp does the same).
float clamp01(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }
Colour clamp01(Colour c) { return {clamp01(c.x), clamp01(c.y), clamp01(c.z)}; }

// sRGB's primaries and D65 white, as exact fractions.
Colour linearRgbToXyz(Colour c) {
  return {(10135552.0f / 24577794.0f) * c.x + (8788810.0f / 24577794.0f) * c.y + (4435075.0f / 24577794.0f) * c.z,
          (2613072.0f / 12288897.0f) * c.x + (8788810.0f / 12288897.0f) * c.y + (887015.0f / 12288897.0f) * c.z,
          (1425312.0f / 73733382.0f) * c.x + (8788810.0f / 73733382.0f) * c.y + (70074185.0f / 73733382.0f) * c.z};
}

Colour xyzToLinearRgb(Colour c) {
  return {3.241003275f * c.x + -1.537398934f * c.y + -0.498615861f * c.z,
          -0.969224334f * c.x + 1.875930071f * c.y + 0.041554224f * c.z,
          0.055639423f * c.x + -0.204011202f * c.y + 1.057148933f * c.z};
}

// YCxCz is L*a*b* without its cube root: linear in XYZ, so that filtering it is
// filtering light (the paper's opponent space, after Zhang and Wandell's S-CIELAB).
Colour xyzToYcxcz(Colour c) {
  const float x = c.x * kInverseWhite[0], y = c.y * kInverseWhite[1], z = c.z * kInverseWhite[2];
  return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

Colour ycxczToXyz(Colour c) {
  const float y = (c.x + 16.0f) / 116.0f;
  const float cx = c.y / 500.0f, cz = c.z / 200.0f;
  return {(y + cx) * kWhite[0], y * kWhite[1], (y - cz) * kWhite[2]};
}

float labCurve(float t) {
  constexpr float delta = 6.0f / 29.0f;
  constexpr float deltaSquared = delta * delta;
  constexpr float deltaCubed = delta * deltaSquared;
  constexpr float slope = 1.0f / (3.0f * deltaSquared);
  return t > deltaCubed ? std::pow(t, 1.0f / 3.0f) : slope * t + 4.0f / 29.0f;
}

Colour xyzToLab(Colour c) {
  const float fx = labCurve(c.x * kInverseWhite[0]);
  const float fy = labCurve(c.y * kInverseWhite[1]);
  const float fz = labCurve(c.z * kInverseWhite[2]);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

// The Hunt effect: chroma looks weaker in the dark, so a and b are scaled by the
// lightness (L / 100).
Colour hunt(Colour lab) { return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z}; }

// HyAB: city-block in lightness, Euclidean in the chroma plane (Abasi et al. 2020),
// which follows large colour differences better than Euclidean L*a*b*.
float hyab(Colour a, Colour b) {
  const float da = a.y - b.y, db = a.z - b.z;
  return std::fabs(a.x - b.x) + std::sqrt(da * da + db * db);
}

Colour perceived(Colour linearRgb) { return hunt(xyzToLab(linearRgbToXyz(linearRgb))); }

// The largest colour distance there is, between pure green and pure blue: the
// scale the distances are mapped to [0, 1] by.
float largestColourDistance() {
  return std::pow(hyab(perceived({0.0f, 1.0f, 0.0f}), perceived({0.0f, 0.0f, 1.0f})), kColourExponent);
}

// Each 1D kernel has 2 * radius + 1 taps, centre at index radius.
struct ColourKernels {
  int radius = 0;
  std::vector<float> achromatic, redGreen, blueYellow1, blueYellow2;
};

float csfWeight(float x2, Csf csf) { return csf.a * std::sqrt(kPi / csf.b) * std::exp(-kPiSquared * x2 / csf.b); }
// The 1D factor of a Gaussian that is one term of a sum: its outer product with
// itself gives the 2D term's weights, so it carries the square root of the scale.
float csfFactor(float x2, Csf csf) {
  return std::sqrt(csf.a * std::sqrt(kPi / csf.b)) * std::exp(-kPiSquared * x2 / csf.b);
}

ColourKernels colourKernels(float ppd) {
  ColourKernels k;
  // Three standard deviations of the widest Gaussian, in pixels.
  k.radius = int(std::ceil(3.0f * std::sqrt(kWidestB / (2.0f * kPiSquared)) * ppd));
  const int taps = 2 * k.radius + 1;
  const float degreesPerPixel = 1.0f / ppd;
  float sumA = 0.0f, sumRg = 0.0f, sumBy1 = 0.0f, sumBy2 = 0.0f;
  for (int i = 0; i < taps; ++i) {
    const float x = float(i - k.radius) * degreesPerPixel;
    const float x2 = x * x;
    k.achromatic.push_back(csfWeight(x2, kAchromatic));
    k.redGreen.push_back(csfWeight(x2, kRedGreen));
    k.blueYellow1.push_back(csfFactor(x2, kBlueYellow1));
    k.blueYellow2.push_back(csfFactor(x2, kBlueYellow2));
    sumA += k.achromatic.back();
    sumRg += k.redGreen.back();
    sumBy1 += k.blueYellow1.back();
    sumBy2 += k.blueYellow2.back();
  }
  // Each 2D filter sums to 1: a separable one when its factor does; the sum of two
  // when the squares of its two factors' sums do.
  const float normA = 1.0f / sumA, normRg = 1.0f / sumRg;
  const float normBy = 1.0f / std::sqrt(sumBy1 * sumBy1 + sumBy2 * sumBy2);
  for (int i = 0; i < taps; ++i) {
    k.achromatic[size_t(i)] *= normA;
    k.redGreen[size_t(i)] *= normRg;
    k.blueYellow1[size_t(i)] *= normBy;
    k.blueYellow2[size_t(i)] *= normBy;
  }
  return k;
}

// The edge and point detectors: a Gaussian of standard deviation g_w / 2 degrees,
// its first derivative and its second, each tap as [gaussian, first, second].
struct FeatureKernels {
  int radius = 0;
  std::vector<std::array<float, 3>> taps;
};

FeatureKernels featureKernels(float ppd) {
  FeatureKernels k;
  const float sigma = 0.5f * kFeatureWidth * ppd;
  k.radius = int(std::ceil(3.0f * sigma));
  float sum = 0.0f, firstUp = 0.0f, firstDown = 0.0f, secondUp = 0.0f, secondDown = 0.0f;
  for (int i = -k.radius; i <= k.radius; ++i) {
    const float x = float(i);
    const float g = std::exp(-(x * x) / (2.0f * sigma * sigma));
    const float first = -x * g;
    const float second = (x * x / (sigma * sigma) - 1.0f) * g;
    sum += g;
    (first > 0.0f ? firstUp : firstDown) += std::fabs(first);
    (second > 0.0f ? secondUp : secondDown) += std::fabs(second);
    k.taps.push_back({g, first, second});
  }
  // The Gaussian sums to 1; each derivative's positive taps to 1 and its negative
  // ones to -1, so that a flat image gives 0 and a unit step the same at any ppd.
  for (auto& t : k.taps) {
    t[0] = t[0] / sum;
    t[1] = t[1] / (t[1] > 0.0f ? firstUp : firstDown);
    t[2] = t[2] / (t[2] > 0.0f ? secondUp : secondDown);
  }
  return k;
}

struct Plane {
  int width = 0, height = 0;
  std::vector<Colour> pixels;
  const Colour& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

Plane toYcxcz(const FloatImage& image) {
  Plane p{image.width, image.height, std::vector<Colour>(size_t(image.width) * size_t(image.height))};
  for (size_t i = 0; i < p.pixels.size(); ++i) {
    const float* c = &image.rgb[i * 3];
    p.pixels[i] = xyzToYcxcz(linearRgbToXyz(clamp01(Colour{c[0], c[1], c[2]})));
  }
  return p;
}

// The images as the eye resolves them: each channel of YCxCz convolved with its
// contrast sensitivity, rows then columns, edges clamped.
Plane spatiallyFiltered(const Plane& in, const ColourKernels& k) {
  const int w = in.width, h = in.height, r = k.radius;
  // Per pixel after the rows: achromatic, red-green, and blue-yellow by each term.
  std::vector<std::array<float, 4>> rows(in.pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::array<float, 4> s{};
      for (int i = -r; i <= r; ++i) {
        const Colour& c = in.at(std::clamp(x + i, 0, w - 1), y);
        const size_t t = size_t(i + r);
        s[0] += k.achromatic[t] * c.x;
        s[1] += k.redGreen[t] * c.y;
        s[2] += k.blueYellow1[t] * c.z;
        s[3] += k.blueYellow2[t] * c.z;
      }
      rows[size_t(y) * size_t(w) + size_t(x)] = s;
    }
  }
  Plane out{w, h, std::vector<Colour>(in.pixels.size())};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::array<float, 4> s{};
      for (int i = -r; i <= r; ++i) {
        const auto& c = rows[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w) + size_t(x)];
        const size_t t = size_t(i + r);
        s[0] += k.achromatic[t] * c[0];
        s[1] += k.redGreen[t] * c[1];
        s[2] += k.blueYellow1[t] * c[2];
        s[3] += k.blueYellow2[t] * c[3];
      }
      out.pixels[size_t(y) * size_t(w) + size_t(x)] = {s[0], s[1], s[2] + s[3]};
    }
  }
  return out;
}

// The colour error of one pixel of the filtered images, in [0, 1]: back to RGB
// (clamped: the filters can leave the gamut), to Hunt-adjusted L*a*b*, HyAB raised
// to q_c, and the map that spends most of [0, 1] on the small differences.
float colourError(Colour filteredReference, Colour filteredTest, float cmax) {
  const auto lab = [](Colour ycxcz) { return perceived(clamp01(xyzToLinearRgb(ycxczToXyz(ycxcz)))); };
  const float distance = std::pow(hyab(lab(filteredReference), lab(filteredTest)), kColourExponent);
  const float knee = kCompressedShare * cmax;
  if (distance < knee) return distance * (kCompressedTo / knee);
  return kCompressedTo + ((distance - knee) / (cmax - knee)) * (1.0f - kCompressedTo);
}

struct Features {
  float edge = 0.0f, point = 0.0f;
};

// Edges and points of the achromatic channel (scaled to [0, 1]): the magnitude of
// the Gaussian's gradient and of its second derivatives, each separated into a
// derivative along one axis and the Gaussian along the other.
std::vector<Features> features(const Plane& in, const FeatureKernels& k) {
  const int w = in.width, h = in.height, r = k.radius;
  // Per pixel after the rows: first and second derivative along x, Gaussian.
  std::vector<std::array<float, 3>> rows(in.pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::array<float, 3> s{};
      for (int i = -r; i <= r; ++i) {
        const float grey = in.at(std::clamp(x + i, 0, w - 1), y).x * (1.0f / 116.0f) + 16.0f / 116.0f;
        const auto& t = k.taps[size_t(i + r)];
        s[0] += t[1] * grey;
        s[1] += t[2] * grey;
        s[2] += t[0] * grey;
      }
      rows[size_t(y) * size_t(w) + size_t(x)] = s;
    }
  }
  std::vector<Features> out(in.pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float dx = 0.0f, ddx = 0.0f, dy = 0.0f, ddy = 0.0f;
      for (int i = -r; i <= r; ++i) {
        const auto& s = rows[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w) + size_t(x)];
        const auto& t = k.taps[size_t(i + r)];
        dx += t[0] * s[0];
        ddx += t[0] * s[1];
        dy += t[1] * s[2];
        ddy += t[2] * s[2];
      }
      out[size_t(y) * size_t(w) + size_t(x)] = {std::sqrt(dx * dx + dy * dy), std::sqrt(ddx * ddx + ddy * ddy)};
    }
  }
  return out;
}

// How much an edge or a point differs, in [0, 1] (1 / sqrt(2) bounds the larger
// difference by 1).
float featureDifference(Features reference, Features test) {
  const float larger = std::max(std::fabs(reference.edge - test.edge), std::fabs(reference.point - test.point));
  return std::min(std::pow((1.0f / std::sqrt(2.0f)) * larger, kFeatureExponent), 1.0f);
}

Status checkPair(int width, int height, int otherWidth, int otherHeight, float ppd) {
  if (width != otherWidth || height != otherHeight)
    return makeError("images differ in size: " + std::to_string(width) + "x" + std::to_string(height) + " vs " +
                     std::to_string(otherWidth) + "x" + std::to_string(otherHeight));
  if (width <= 0 || height <= 0) return makeError("empty images");
  if (!(ppd > 0.0f) || !std::isfinite(ppd))
    return makeError("pixels per degree must be a positive number, got " + std::to_string(ppd));
  return Ok{};
}

}  // namespace

Result<FlipMap> ldrFlip(const FloatImage& reference, const FloatImage& test, float ppd) {
  if (auto s = checkPair(reference.width, reference.height, test.width, test.height, ppd); !s) return s.error();
  const Plane ref = toYcxcz(reference), tst = toYcxcz(test);
  const ColourKernels colour = colourKernels(ppd);
  const Plane refSeen = spatiallyFiltered(ref, colour), testSeen = spatiallyFiltered(tst, colour);
  const FeatureKernels feature = featureKernels(ppd);
  const std::vector<Features> refFeatures = features(ref, feature), testFeatures = features(tst, feature);
  const float cmax = largestColourDistance();
  FlipMap map{reference.width, reference.height, std::vector<float>(ref.pixels.size())};
  for (size_t i = 0; i < map.error.size(); ++i) {
    const float colour01 = colourError(refSeen.pixels[i], testSeen.pixels[i], cmax);
    // A feature in one image and not the other lifts the error toward 1.
    map.error[i] = std::pow(colour01, 1.0f - featureDifference(refFeatures[i], testFeatures[i]));
  }
  return map;
}

Result<FlipMap> ldrFlip(const Image& reference, const Image& test, float ppd) {
  if (auto s = checkPair(reference.width, reference.height, test.width, test.height, ppd); !s) return s.error();
  return ldrFlip(linearFromSrgb(reference), linearFromSrgb(test), ppd);
}

FloatImage linearFromSrgb(const Image& image) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  FloatImage out;
  out.width = image.width;
  out.height = image.height;
  const size_t count = size_t(image.width) * size_t(image.height);
  out.rgb.resize(count * 3);
  for (size_t i = 0; i < count; ++i)
    for (size_t c = 0; c < 3; ++c) out.rgb[i * 3 + c] = table[image.pixels[i * 4 + c]];
  return out;
}

}  // namespace engine
