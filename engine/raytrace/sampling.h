#pragma once
// The path tracer's sampling routines, each with the density it draws from: the
// estimator divides by exactly that pdf, and tests/raytrace/sampling_test.cpp checks
// every pair with a chi-square test. The routines are shaders/common/sampling.glsl,
// the GPU path tracer's text, compiled as C++ (core/sampling.h); here they get the
// names and the Frame class the CPU's callers use. Directions are in a local frame
// with the normal along +z (Frame maps to and from the world); solid-angle densities
// throughout. The distributions below have their GPU side in
// shaders/rt/environment_light.glsl, which reads their tables from a buffer.
#include <numbers>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/sampling.h"

namespace engine::rt {

inline constexpr float kPi = std::numbers::pi_v<float>;

// An orthonormal basis around a unit normal (sampling.glsl's frameAbout, Duff et
// al. 2017), or around a normal with s along a tangent (frameAlong).
struct Frame : brdf::Frame {
  // s along `tangent` made orthogonal to the normal (unit, non-zero), t = n x s.
  Frame(const glm::vec3& normal, const glm::vec3& tangent) : brdf::Frame(brdf::frameAlong(normal, tangent)) {}
  explicit Frame(const glm::vec3& normal) : brdf::Frame(brdf::frameAbout(normal)) {}
  glm::vec3 toLocal(const glm::vec3& w) const { return brdf::toLocal(*this, w); }
  glm::vec3 toWorld(const glm::vec3& w) const { return brdf::toWorld(*this, w); }
};

using brdf::cosineHemispherePdf;
using brdf::cosSinQuarter;
using brdf::ggxAnisotropicD;
using brdf::ggxAnisotropicG1;
using brdf::ggxAnisotropicReflectionPdf;
using brdf::ggxD;
using brdf::ggxLambda;
using brdf::ggxReflectionPdf;
using brdf::ggxSmithG1;
using brdf::powerHeuristic;
using brdf::reflectAbout;
using brdf::sampleCosineHemisphere;
using brdf::sampleGgxAnisotropicVisibleNormal;
using brdf::sampleGgxVisibleNormal;
using brdf::sampleUniformCone;
using brdf::uniformConePdf;

// A piecewise-constant density on [0, 1) from non-negative weights (pbrt's
// Distribution1D): sample() inverts its CDF, pdf() is the density at a point.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);
  // A point in [0, 1) and the index of its cell; the density there is pdf(index).
  float sample(float u, int* index) const;
  float pdf(int index) const { return integral_ > 0.0f ? func_[std::size_t(index)] / integral_ : 0.0f; }
  float integral() const { return integral_; }  // mean weight: the weights' integral over [0, 1)
  int size() const { return int(func_.size()); }
  // The tables as sample() and pdf() read them (the GPU path tracer uploads them).
  std::span<const float> func() const { return func_; }
  std::span<const float> cdf() const { return cdf_; }

 private:
  std::vector<float> func_;
  std::vector<float> cdf_;  // size + 1, from 0 to 1
  float integral_ = 0.0f;
};

// The same on [0, 1)^2 from a width x height grid of weights, top row first: a
// marginal density over rows and a conditional one within each.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, int width, int height);
  glm::vec2 sample(glm::vec2 u, float* pdf) const;
  float pdf(glm::vec2 p) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const Distribution1D& marginal() const { return marginal_; }
  const Distribution1D& row(int y) const { return rows_[std::size_t(y)]; }

 private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
  int width_ = 0, height_ = 0;
};

}  // namespace engine::rt
