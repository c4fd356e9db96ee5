#pragma once
// PCG32 (O'Neill, pcg-random.org, the minimal "XSH RR" generator) and a hash that
// gives every pixel its own stream. Each pixel's random numbers depend only on
// (seed, x, y), never on which thread or in which order the pixel is rendered, so
// an image is the same bytes with 1 thread or 16.
#include <cstdint>

#include <glm/glm.hpp>

namespace engine::rt {

// SplitMix64's finaliser: a bijective mix so that neighbouring pixels get unrelated
// PCG states.
inline std::uint64_t mixBits(std::uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ull;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dull;
  v ^= v >> 33;
  return v;
}

class Pcg32 {
 public:
  Pcg32() = default;  // a placeholder to assign a seeded generator to
  Pcg32(std::uint64_t seed, std::uint64_t stream) { setSequence(seed, stream); }

  // A generator for pixel (x, y) of an image rendered with `seed`.
  static Pcg32 forPixel(std::uint64_t seed, int x, int y) {
    const std::uint64_t key = (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y);
    return Pcg32(mixBits(seed ^ mixBits(key)), mixBits(key + 0x9e3779b97f4a7c15ull));
  }

  // A generator for sample `sample` of pixel (x, y): every sample has a stream of its
  // own, so a pixel's first N samples are the same whether it is rendered with N spp
  // at once or in passes (the progressive window, the convergence benchmark).
  static Pcg32 forSample(std::uint64_t seed, int x, int y, int sample) {
    const std::uint64_t key = (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y);
    return Pcg32(mixBits(seed ^ mixBits(key) ^ mixBits(std::uint64_t(std::uint32_t(sample)) + 0x632be59bd9b4e019ull)),
                 mixBits(key + 0x9e3779b97f4a7c15ull));
  }

  std::uint32_t nextU32() {
    const std::uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    const auto xorShifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    const auto rot = std::uint32_t(old >> 59u);
    return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31u));
  }

  // Uniform in [0, 1): 24 random bits, so the largest value is 1 - 2^-24 < 1.
  float uniform() { return float(nextU32() >> 8) * 0x1p-24f; }
  // Two draws as a 2D sample, in a fixed order: the first is y, the second x. Written
  // as vec2(uniform(), uniform()) the order is unspecified in C++: g++ drew y first
  // (the order the path-traced goldens were made in), clang x first, and the same
  // seed gave another image (the clang sanitizer build's pathtrace goldens failed).
  glm::vec2 uniform2() {
    const float y = uniform();
    const float x = uniform();
    return {x, y};
  }

 private:
  static constexpr std::uint64_t kMultiplier = 0x5851f42d4c957f2dull;

  void setSequence(std::uint64_t seed, std::uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    nextU32();
    state_ += seed;
    nextU32();
  }

  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

}  // namespace engine::rt
