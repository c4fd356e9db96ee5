// The phase functions of participating media (shaders/common/phase.glsl through
// core/phase.h): each sampler against its density by a chi-square test (a million
// samples, 80 x 160 cells, alpha = 0.01 over these cases by Sidak's correction), and
// each density by quadrature over the sphere: it integrates to 1, and
// Henyey-Greenstein's mean cosine is its g, at the extremes of g too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "chi_square.h"
#include "core/phase.h"
#include "../support/quadrature.h"

namespace brdf = engine::brdf;

namespace {

constexpr float kGs[] = {-0.9f, -0.5f, -1e-4f, 0.0f, 0.3f, 0.8f, 0.95f};
constexpr int kChiSquareCases = int(sizeof(kGs) / sizeof(kGs[0])) + 1;
const double kSignificance = chi2::sidak(0.01, kChiSquareCases);

void expectPasses(const chi2::Result& r) {
  EXPECT_GT(r.degreesOfFreedom, 0) << r.message;
  EXPECT_GT(r.pValue, kSignificance) << r.message;
}

TEST(ChiSquare, HenyeyGreenstein) {
  for (const float g : kGs) {
    SCOPED_TRACE("g = " + std::to_string(g));
    expectPasses(chi2::test(
        [g](glm::vec2 u, glm::vec3* w) {
          *w = brdf::samplePhaseHenyeyGreenstein(u, g);
          return true;
        },
        [g](const glm::vec3& w) { return double(brdf::phaseHenyeyGreenstein(w.z, g)); }));
  }
}

TEST(ChiSquare, Rayleigh) {
  expectPasses(chi2::test(
      [](glm::vec2 u, glm::vec3* w) {
        *w = brdf::samplePhaseRayleigh(u);
        return true;
      },
      [](const glm::vec3& w) { return double(brdf::phaseRayleigh(w.z)); }));
}

// 2 pi times the integral over cos theta in [-1, 1] of f(mu), adaptive to 1e-9:
// Henyey-Greenstein's peak at g = 0.99 is 1e-4 wide in mu, which a uniform grid
// misses.
template <typename F>
double overTheSphere(F f) {
  return 2.0 * 3.14159265358979323846 * engine::test::integrate(f, -1.0, 1.0, 1e-9);
}

// Limits: 1e-5 for the integrals and the mean cosine, the rounding of a density
// evaluated in float at every point (measured below 1e-6).
TEST(Phase, EachDensityIntegratesToOneAndHenyeyGreensteinsMeanCosineIsG) {
  for (const float g : {-0.99f, -0.9f, -0.5f, 0.0f, 1e-4f, 0.3f, 0.8f, 0.95f, 0.99f}) {
    SCOPED_TRACE("g = " + std::to_string(g));
    const double total = overTheSphere([g](double mu) { return double(brdf::phaseHenyeyGreenstein(float(mu), g)); });
    const double mean = overTheSphere([g](double mu) { return mu * double(brdf::phaseHenyeyGreenstein(float(mu), g)); });
    EXPECT_NEAR(total, 1.0, 1e-5);
    EXPECT_NEAR(mean, double(g), 1e-5);
  }
  EXPECT_NEAR(overTheSphere([](double mu) { return double(brdf::phaseRayleigh(float(mu))); }), 1.0, 1e-6);
  EXPECT_NEAR(overTheSphere([](double mu) { return mu * double(brdf::phaseRayleigh(float(mu))); }), 0.0, 1e-6);
}

// Henyey-Greenstein near its peak at strong g (where the textbook denominator
// cancelled): against the density in double of the same float inputs, over g to
// +-0.9999 and the 4096 floats of cos nearest the peak and a sweep across [-1, 1].
// Limit: 1e-6 relative, a few float roundings (measured 3e-7).
TEST(Phase, HenyeyGreensteinKeepsItsDigitsAtItsPeak) {
  double worst = 0.0;
  for (const float g : {-0.9999f, -0.999f, -0.99f, -0.9f, 0.9f, 0.99f, 0.999f, 0.9999f}) {
    const float peak = g > 0.0f ? 1.0f : -1.0f;
    float c = peak;
    for (int i = 0; i < 4096 + 2048; ++i) {
      c = i < 4096 ? c : peak - float(i - 4096) / 1024.0f * peak;
      const double gd = g, cd = c, denom = 1.0 + gd * gd - 2.0 * gd * cd;
      const double truth = (1.0 - gd * gd) / (4.0 * 3.14159265358979323846 * denom * std::sqrt(denom));
      worst = std::max(worst, std::abs(double(brdf::phaseHenyeyGreenstein(c, g)) - truth) / truth);
      if (i < 4096) c = std::nextafter(c, -peak);
    }
  }
  std::printf("henyey-greenstein at its peak: worst relative error %.3g\n", worst);
  EXPECT_LE(worst, 1e-6);
}

// The samplers' cosines stay in [-1, 1] and their directions unit, over a sweep of u
// to both ends and of g to +-0.999; the inverted CDFs give their ends: Rayleigh's
// u = 0 is straight back and u = 1 straight on, Henyey-Greenstein's (pbrt-v4's form)
// the other way round.
TEST(Phase, SamplesAreUnitAtEveryEnd) {
  for (int i = 0; i <= 4096; ++i) {
    const float u = i == 4096 ? 0.99999994f : float(i) / 4096.0f;
    for (const float g : {-0.999f, -0.5f, 0.0f, 0.5f, 0.999f}) {
      const glm::vec3 w = brdf::samplePhaseHenyeyGreenstein(glm::vec2(u, 0.37f), g);
      ASSERT_NEAR(glm::length(w), 1.0f, 1e-6f) << "u " << u << ", g " << g;
      ASSERT_TRUE(w.z >= -1.0f && w.z <= 1.0f);
    }
    const glm::vec3 r = brdf::samplePhaseRayleigh(glm::vec2(u, 0.71f));
    ASSERT_NEAR(glm::length(r), 1.0f, 1e-6f) << "u " << u;
  }
  EXPECT_FLOAT_EQ(brdf::sampleRayleighCosine(0.0f), -1.0f);
  EXPECT_FLOAT_EQ(brdf::sampleRayleighCosine(0.5f), 0.0f);
  EXPECT_NEAR(brdf::sampleRayleighCosine(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(brdf::sampleHenyeyGreensteinCosine(0.0f, 0.5f), 1.0f, 1e-6f);
  EXPECT_NEAR(brdf::sampleHenyeyGreensteinCosine(1.0f, 0.5f), -1.0f, 1e-6f);
}

}  // namespace
