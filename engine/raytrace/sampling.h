#pragma once
// The path tracer's sampling routines, each with the density it draws from: the
// estimator divides by exactly that pdf, and tests/raytrace/sampling_test.cpp checks
// every pair with a chi-square test. shaders/rt/sampling.glsl and
// environment_light.glsl transcribe what the GPU path tracer uses of them: a change
// here is a change there (tests/gl/gpu_path_test.cpp compares the two tracers). Directions are in a local frame with the normal
// along +z (Frame maps to and from the world); solid-angle densities throughout.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/ggx_sampling.h"  // ggxLambda, ggxSmithG1, sampleGgxVisibleNormal

namespace engine::rt {

inline constexpr float kPi = std::numbers::pi_v<float>;
// Shared with the split-sum table (core/ggx_sampling.h); tested here.
using engine::ggxLambda;
using engine::ggxSmithG1;
using engine::sampleGgxVisibleNormal;

// An orthonormal basis around a unit normal (Duff et al., "Building an Orthonormal
// Basis, Revisited", JCGT 2017): no branch on which axis is smallest, no
// normalisation, and no precision loss near either pole.
struct Frame {
  glm::vec3 s, t, n;

  // s along `tangent` made orthogonal to the normal (unit, non-zero), t = n x s.
  Frame(const glm::vec3& normal, const glm::vec3& tangent)
      : s(glm::normalize(tangent - normal * glm::dot(normal, tangent))), t(glm::cross(normal, s)), n(normal) {}
  explicit Frame(const glm::vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = glm::vec3(b, sign + n.y * n.y * a, -n.y);
  }
  glm::vec3 toLocal(const glm::vec3& w) const { return {glm::dot(w, s), glm::dot(w, t), glm::dot(w, n)}; }
  glm::vec3 toWorld(const glm::vec3& w) const { return w.x * s + w.y * t + w.z * n; }
};

// (cos a, sin a) for |a| <= pi / 4, by their Taylor polynomials to a^8 and a^9 (the
// first terms left out are below 2.5e-8 and 3.1e-7 there; within 3 ulps of the true
// values, SamplingTest.QuarterSinCosIsWithinThreeUlps). libm's sincosf reduces any
// argument and was 3-4 % of the path tracer's time on the course room.
inline glm::vec2 cosSinQuarter(float a) {
  const float a2 = a * a;
  const float c = 1.0f + a2 * (-1.0f / 2 + a2 * (1.0f / 24 + a2 * (-1.0f / 720 + a2 * (1.0f / 40320))));
  const float s = a * (1.0f + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040 + a2 * (1.0f / 362880)))));
  return {c, s};
}

// Malley's method: a uniform point on the disk lifted to the hemisphere; pdf cos / pi.
inline glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  // Shirley and Chiu's concentric map keeps strata compact (no squashing at the rim).
  const glm::vec2 o = 2.0f * u - 1.0f;
  glm::vec2 d(0.0f);
  if (o.x != 0.0f || o.y != 0.0f) {
    // Each branch's operations chosen by selects, not jumps: which axis is major is a
    // coin toss per sample, and a jump on it was mispredicted half the time. The
    // minor axis's angle a is within pi / 4 of the major axis: (cos a, sin a) about
    // x, or (cos(pi/2 - a), sin(pi/2 - a)) = (sin a, cos a) about y.
    const bool xMajor = std::abs(o.x) > std::abs(o.y);
    const float r = xMajor ? o.x : o.y, other = xMajor ? o.y : o.x;
    const glm::vec2 cs = cosSinQuarter((kPi / 4.0f) * (other / r));
    d = r * (xMajor ? cs : glm::vec2(cs.y, cs.x));
  }
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(cosTheta, 0.0f) / kPi; }

// Uniform over the cone of directions within acos(cosMax) of +z; pdf 1 / (2 pi (1 - cosMax)).
inline glm::vec3 sampleUniformCone(glm::vec2 u, float cosMax) {
  const float cosTheta = (1.0f - u.x) + u.x * cosMax;
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * u.y;
  return {std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, cosTheta};
}
inline float uniformConePdf(float cosMax) { return 1.0f / (2.0f * kPi * (1.0f - cosMax)); }

// D(h) for a local h, in core/brdf.h's stable form (sin^2 from x and y, not 1 - cos^2).
inline float ggxD(const glm::vec3& h, float alpha) {
  const float a = h.z * alpha;
  const float k = alpha / std::max(h.x * h.x + h.y * h.y + a * a, 1e-30f);
  return k * k / kPi;
}

// The density of wi = reflect(-wo, h) with h from sampleGgxVisibleNormal:
// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
inline float ggxReflectionPdf(const glm::vec3& wo, const glm::vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(wo + wi);
  return ggxSmithG1(wo.z, alpha) * ggxD(h, alpha) / (4.0f * wo.z);
}

// The same for the anisotropic GGX (alpha.x along x, alpha.y along y).
inline float ggxAnisotropicD(const glm::vec3& h, glm::vec2 alpha) {
  const float a2 = alpha.x * alpha.y;
  const glm::vec3 f(alpha.y * h.x, alpha.x * h.y, a2 * h.z);
  const float w2 = a2 / std::max(glm::dot(f, f), 1e-30f);
  return a2 * w2 * w2 / kPi;
}
inline float ggxAnisotropicReflectionPdf(const glm::vec3& wo, const glm::vec3& wi, glm::vec2 alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const glm::vec3 h = glm::normalize(wo + wi);
  return ggxAnisotropicG1(wo, alpha) * ggxAnisotropicD(h, alpha) / (4.0f * wo.z);
}

inline glm::vec3 reflectAbout(const glm::vec3& w, const glm::vec3& h) { return 2.0f * glm::dot(w, h) * h - w; }

// Veach's power heuristic (beta = 2) for a sample of strategy f, with one sample
// taken from each of the two strategies.
inline float powerHeuristic(float fPdf, float gPdf) {
  const float f2 = fPdf * fPdf, g2 = gPdf * gPdf;
  return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
}

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
