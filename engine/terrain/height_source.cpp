#include "terrain/height_source.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/image.h"

namespace engine::terrain {
namespace {

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Quintic fade: C2 smooth, and its value stays in [0, 1], so interpolation with it
// is a convex combination of the lattice values.
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// A sample's lattice cell along one axis and its faded fraction in it. Integer
// division keeps both exact.
struct CellAt {
  std::int64_t cell;
  double fade;
};
CellAt cellAt(int i, int period) {
  const std::int64_t c = floorDiv(i, period);
  return {c, fade(double(i - c * period) / period)};
}

// The bilinear blend of a cell's four lattice values, written once for sample() and
// sampleGrid() so that both round alike.
double blend(double v00, double v10, double v01, double v11, double fx, double fz) {
  const double a = v00 + (v10 - v00) * fx;
  const double b = v01 + (v11 - v01) * fx;
  return a + (b - a) * fz;
}

double valueNoise(std::uint32_t seed, int octave, int period, int ix, int iz) {
  const CellAt x = cellAt(ix, period), z = cellAt(iz, period);
  return blend(latticeValue(seed, octave, x.cell, z.cell), latticeValue(seed, octave, x.cell + 1, z.cell),
               latticeValue(seed, octave, x.cell, z.cell + 1), latticeValue(seed, octave, x.cell + 1, z.cell + 1),
               x.fade, z.fade);
}

// One axis of a grid for one octave: each sample's cell and fade, and the lattice
// coordinates the grid touches (every cell and the one after it), sorted, with each
// sample's cell as an index into them (its next cell is the index after).
struct GridAxis {
  std::vector<std::int64_t> lattice;
  std::vector<std::size_t> index;
  std::vector<double> fades;
  GridAxis(std::span<const int> at, int period) {
    std::vector<CellAt> cells;
    for (int i : at) {
      cells.push_back(cellAt(i, period));
      lattice.push_back(cells.back().cell);
      lattice.push_back(cells.back().cell + 1);
    }
    std::sort(lattice.begin(), lattice.end());
    lattice.erase(std::unique(lattice.begin(), lattice.end()), lattice.end());
    for (const CellAt& c : cells) {
      index.push_back(std::size_t(std::lower_bound(lattice.begin(), lattice.end(), c.cell) - lattice.begin()));
      fades.push_back(c.fade);
    }
  }
};

// Float storage rounds the double result; one ulp outward keeps the bound honest.
HeightRange widen(double lo, double hi) {
  return {std::nextafter(float(lo), -std::numeric_limits<float>::infinity()),
          std::nextafter(float(hi), std::numeric_limits<float>::infinity())};
}

}  // namespace

double latticeValue(std::uint32_t seed, int octave, std::int64_t x, std::int64_t z) {
  std::uint64_t k = splitMix64(std::uint64_t(seed) ^ (std::uint64_t(unsigned(octave)) << 40));
  k = splitMix64(k ^ std::uint64_t(x));
  k = splitMix64(k ^ std::uint64_t(z));
  return double(k >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // 53 bits -> [-1, 1)
}

NoiseHeights::NoiseHeights(const NoiseParams& params) : params_(params) {
  // Octaves end where the period would drop under two samples: finer ones alias.
  int period = params_.basePeriod;
  int octaves = 0;
  double amplitude = 1.0;
  while (octaves < params_.octaves && period >= 2) {
    amplitudeSum_ += amplitude;
    amplitude *= 0.5;
    period /= 2;
    ++octaves;
  }
  params_.octaves = octaves;
  if (amplitudeSum_ == 0.0) amplitudeSum_ = 1.0;
}

// Monotonic, so bounds on the fBm sum map straight to bounds on heights. The
// t * sqrt(t) flattens valleys and sharpens peaks; sqrt is correctly rounded
// everywhere, unlike pow.
double NoiseHeights::shape(double fbm) const {
  const double t = std::clamp(0.5 + 0.8 * fbm / amplitudeSum_, 0.0, 1.0);
  return params_.heightScale * (t * std::sqrt(t));
}

float NoiseHeights::sample(int ix, int iz) const {
  double sum = 0.0, amplitude = 1.0;
  int period = params_.basePeriod;
  for (int o = 0; o < params_.octaves; ++o) {
    sum += amplitude * valueNoise(params_.seed, o, period, ix, iz);
    amplitude *= 0.5;
    period /= 2;
  }
  return float(shape(sum));
}

void NoiseHeights::sampleGrid(std::span<const int> xs, std::span<const int> zs, std::span<float> out) const {
  std::vector<double> sums(xs.size() * zs.size(), 0.0);
  std::vector<double> values;
  double amplitude = 1.0;
  int period = params_.basePeriod;
  for (int o = 0; o < params_.octaves; ++o) {
    const GridAxis gx(xs, period), gz(zs, period);
    const std::size_t row = gx.lattice.size();
    values.resize(row * gz.lattice.size());
    for (std::size_t j = 0; j < gz.lattice.size(); ++j) {
      for (std::size_t i = 0; i < row; ++i) values[j * row + i] = latticeValue(params_.seed, o, gx.lattice[i], gz.lattice[j]);
    }
    for (std::size_t j = 0; j < zs.size(); ++j) {
      const double* v0 = &values[gz.index[j] * row];
      const double* v1 = v0 + row;
      for (std::size_t i = 0; i < xs.size(); ++i) {
        const std::size_t k = gx.index[i];
        sums[j * xs.size() + i] += amplitude * blend(v0[k], v0[k + 1], v1[k], v1[k + 1], gx.fades[i], gz.fades[j]);
      }
    }
    amplitude *= 0.5;
    period /= 2;
  }
  for (std::size_t s = 0; s < sums.size(); ++s) out[s] = float(shape(sums[s]));
}

HeightRange NoiseHeights::bounds(int ix0, int iz0, int ix1, int iz1) const {
  // Scanning more lattice points than this costs more than the tighter bound is
  // worth; such octaves are fine enough that [-1, 1] is nearly their range anyway.
  constexpr std::int64_t kMaxLatticeScan = 256;
  double lo = 0.0, hi = 0.0, amplitude = 1.0;
  int period = params_.basePeriod;
  for (int o = 0; o < params_.octaves; ++o) {
    const std::int64_t lx0 = floorDiv(ix0, period), lx1 = floorDiv(ix1, period) + 1;
    const std::int64_t lz0 = floorDiv(iz0, period), lz1 = floorDiv(iz1, period) + 1;
    double vmin = -1.0, vmax = 1.0;
    if ((lx1 - lx0 + 1) * (lz1 - lz0 + 1) <= kMaxLatticeScan) {
      vmin = 1.0;
      vmax = -1.0;
      for (std::int64_t z = lz0; z <= lz1; ++z) {
        for (std::int64_t x = lx0; x <= lx1; ++x) {
          const double v = latticeValue(params_.seed, o, x, z);
          vmin = std::min(vmin, v);
          vmax = std::max(vmax, v);
        }
      }
    }
    lo += amplitude * vmin;
    hi += amplitude * vmax;
    amplitude *= 0.5;
    period /= 2;
  }
  return widen(shape(lo), shape(hi));
}

void HeightSource::sampleGrid(std::span<const int> xs, std::span<const int> zs, std::span<float> out) const {
  for (std::size_t j = 0; j < zs.size(); ++j) {
    for (std::size_t i = 0; i < xs.size(); ++i) out[j * xs.size() + i] = sample(xs[i], zs[j]);
  }
}

ImageHeights::ImageHeights(int width, int height, std::vector<std::uint16_t> samples,
                           float heightScale)
    : width_(width), height_(height), samples_(std::move(samples)),
      scale_(heightScale / 65535.0f) {
  blocksX_ = (width_ - 1) / kBlock + 1;
  blocksZ_ = (height_ - 1) / kBlock + 1;
  blocks_.assign(size_t(blocksX_) * blocksZ_, HeightRange{std::numeric_limits<float>::max(),
                                                          std::numeric_limits<float>::lowest()});
  global_ = blocks_[0];
  for (int z = 0; z < height_; ++z) {
    for (int x = 0; x < width_; ++x) {
      const float h = sample(x, z);
      // A sample on a block's far edge belongs to both blocks, so any region is
      // covered by the blocks its corner samples fall in.
      for (int bz = std::max(0, (z - 1) / kBlock); bz <= std::min(blocksZ_ - 1, z / kBlock); ++bz) {
        for (int bx = std::max(0, (x - 1) / kBlock); bx <= std::min(blocksX_ - 1, x / kBlock); ++bx) {
          HeightRange& b = blocks_[size_t(bz) * blocksX_ + bx];
          b.min = std::min(b.min, h);
          b.max = std::max(b.max, h);
        }
      }
      global_.min = std::min(global_.min, h);
      global_.max = std::max(global_.max, h);
    }
  }
}

float ImageHeights::sample(int ix, int iz) const {
  return float(samples_[size_t(iz) * width_ + ix]) * scale_;
}

HeightRange ImageHeights::bounds(int ix0, int iz0, int ix1, int iz1) const {
  HeightRange r{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
  const int bx1 = std::min(blocksX_ - 1, ix1 / kBlock), bz1 = std::min(blocksZ_ - 1, iz1 / kBlock);
  for (int bz = std::min(iz0 / kBlock, bz1); bz <= bz1; ++bz) {
    for (int bx = std::min(ix0 / kBlock, bx1); bx <= bx1; ++bx) {
      const HeightRange& b = blocks_[size_t(bz) * blocksX_ + bx];
      r.min = std::min(r.min, b.min);
      r.max = std::max(r.max, b.max);
    }
  }
  return r;
}

Result<std::unique_ptr<ImageHeights>> loadHeightmap(const std::string& path, float heightScale) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return makeError(path + ": cannot open heightmap");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
  if (bytes.empty()) return makeError(path + ": heightmap file is empty");
  if (Status header = checkPngHeader(bytes, path); !header) return header.error();
  std::vector<std::uint8_t> padded;
  const auto png = withFullPalette(bytes, padded);
  const auto* data = png.data();
  const int size = int(png.size());
  int w = 0, h = 0, channels = 0;
  std::vector<std::uint16_t> samples;
  if (stbi_is_16_bit_from_memory(data, size)) {
    stbi_us* pixels = stbi_load_16_from_memory(data, size, &w, &h, &channels, 1);
    if (!pixels) return makeError(path + ": cannot decode heightmap: " + stbi_failure_reason());
    samples.assign(pixels, pixels + size_t(w) * h);
    stbi_image_free(pixels);
  } else {
    stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &channels, 1);
    if (!pixels) return makeError(path + ": cannot decode heightmap: " + stbi_failure_reason());
    samples.resize(size_t(w) * h);
    for (size_t i = 0; i < samples.size(); ++i) samples[i] = std::uint16_t(pixels[i] * 257u);
    stbi_image_free(pixels);
  }
  if (w < 2 || h < 2) {
    return makeError(path + ": heightmap is " + std::to_string(w) + "x" + std::to_string(h) +
                     " samples; at least 2x2 are needed");
  }
  return std::make_unique<ImageHeights>(w, h, std::move(samples), heightScale);
}

}  // namespace engine::terrain
