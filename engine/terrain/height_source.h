#pragma once
// Where terrain heights come from: a decoded PNG (8 or 16 bit grey) or seeded
// fractal value noise. Both answer point samples at integer sample indices and
// rigorous height bounds over a rectangle of samples, which frustum culling needs
// before any page of the region has been generated.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"

namespace engine::terrain {

// Heights in metres above the terrain origin; `min <= h <= max` for every sample
// in the region asked about.
struct HeightRange {
  float min = 0.0f;
  float max = 0.0f;
};

class HeightSource {
 public:
  virtual ~HeightSource() = default;
  // Sample at integer indices; callers clamp them to [0, cells].
  virtual float sample(int ix, int iz) const = 0;
  // The samples at every (xs[i], zs[j]), row by row: out[j * xs.size() + i], each
  // the value sample() gives. Pages and error scans ask for grids this way.
  virtual void sampleGrid(std::span<const int> xs, std::span<const int> zs, std::span<float> out) const;
  // Bounds over the samples [ix0, ix1] x [iz0, iz1] (inclusive, clamped indices).
  virtual HeightRange bounds(int ix0, int iz0, int ix1, int iz1) const = 0;
  // Bounds over every sample.
  virtual HeightRange globalBounds() const = 0;
};

// Fractal sum (fBm) of value noise on integer-hashed lattices. Value noise rather
// than gradient noise because its smooth interpolation is a convex combination of
// the lattice values, so the lattice values bound each octave over a region: that
// is what makes `bounds` rigorous. Everything is integer hashing and IEEE double
// arithmetic on power-of-two lattice periods, so a seed gives the same heights on
// every machine.
struct NoiseParams {
  std::uint32_t seed = 1;
  int basePeriod = 1024;  // samples per lattice cell of the first octave; a power of two
  int octaves = 10;       // each halves the period and the amplitude
  float heightScale = 400.0f;
};

class NoiseHeights final : public HeightSource {
 public:
  explicit NoiseHeights(const NoiseParams& params);
  float sample(int ix, int iz) const override;
  // sample()'s values bit for bit, with each octave's lattice values hashed once for
  // the grid where sample() hashes four a sample.
  void sampleGrid(std::span<const int> xs, std::span<const int> zs, std::span<float> out) const override;
  HeightRange bounds(int ix0, int iz0, int ix1, int iz1) const override;
  HeightRange globalBounds() const override { return {0.0f, params_.heightScale}; }

 private:
  double shape(double fbm) const;
  NoiseParams params_;
  double amplitudeSum_ = 0.0;
};

// A grey PNG decoded whole (2 bytes a sample); PNG cannot be read in parts, so this
// source is resident and only its pages are cached like any other's.
class ImageHeights final : public HeightSource {
 public:
  // 8-bit images are widened to 16 bits (v * 257) so both depths share one path.
  ImageHeights(int width, int height, std::vector<std::uint16_t> samples, float heightScale);
  float sample(int ix, int iz) const override;
  HeightRange bounds(int ix0, int iz0, int ix1, int iz1) const override;
  HeightRange globalBounds() const override { return global_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  static constexpr int kBlock = 32;  // min/max kept per 32x32-sample block
  int width_ = 0, height_ = 0;
  std::vector<std::uint16_t> samples_;
  float scale_ = 0.0f;
  int blocksX_ = 0, blocksZ_ = 0;
  std::vector<HeightRange> blocks_;
  HeightRange global_;
};

// Reads an 8- or 16-bit PNG (any channel count; colour is converted to grey) with
// the header checked first against the core's image limits. Errors name the file.
Result<std::unique_ptr<ImageHeights>> loadHeightmap(const std::string& path, float heightScale);

// The lattice hash behind the noise, exposed for determinism tests: a value in
// [-1, 1] for lattice point (x, z) of `octave`.
double latticeValue(std::uint32_t seed, int octave, std::int64_t x, std::int64_t z);

}  // namespace engine::terrain
