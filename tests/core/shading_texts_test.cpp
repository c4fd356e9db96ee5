// The tracers' texts beside the BRDF, two compilers each: common/sampling.glsl,
// common/view_layers.glsl, common/sky.glsl, common/spot_cone.glsl, common/phase.glsl,
// common/atmosphere.glsl
// and common/terrain_layers.glsl run by the
// GPU's GLSL compiler in a compute shader (test/*_eval.comp) and by the C++ build of
// the same text (core/sampling.h, core/view_layers.h, core/sky.h,
// terrain/materials.h: what the CPU tracers call) over
// random normals, directions, roughnesses, uniform numbers and layers: every
// routine of the texts, each with the same inputs on both sides.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "../support/gl_test.h"
#include "../support/random_draws.h"
#include "core/atmosphere.h"
#include "core/layer_texels.h"
#include "core/sampling.h"
#include "core/phase.h"
#include "core/sky.h"
#include "core/spot_cone.h"
#include "core/view_layers.h"
#include "terrain/materials.h"

using namespace engine;
using engine::test::GlTest;

namespace {

struct SamplingCase {
  glm::vec4 n, tangent, w, wi, u, disk;
};
struct SamplingResult {
  glm::vec4 aboutS, aboutT, alongS, alongT, local, world, cosine, cone, visible, anisotropic, reflected, pdfs, lambdas,
      visibleAt;
};
constexpr int kSamplingValues = int(sizeof(SamplingResult) / sizeof(glm::vec4));

// What sampling_eval.comp computes, by the C++ build of the text.
SamplingResult samplingOnCpu(const SamplingCase& c) {
  const glm::vec3 n(c.n), w(c.w), wi(c.wi);
  const glm::vec2 u(c.u), alphas(c.w.w, c.wi.w);
  const float alpha = c.w.w, cosMax = c.tangent.w;
  const brdf::Frame about = brdf::frameAbout(n), along = brdf::frameAlong(n, glm::vec3(c.tangent));
  const glm::vec2 cs = brdf::cosSinQuarter(c.n.w);
  SamplingResult r;
  r.aboutS = glm::vec4(about.s, 0.0f);
  r.aboutT = glm::vec4(about.t, 0.0f);
  r.alongS = glm::vec4(along.s, 0.0f);
  r.alongT = glm::vec4(along.t, 0.0f);
  r.local = glm::vec4(brdf::toLocal(about, w), cs.x);
  r.world = glm::vec4(brdf::toWorld(about, w), cs.y);
  r.cosine = glm::vec4(brdf::sampleCosineHemisphere(u), brdf::cosineHemispherePdf(wi.z));
  r.cone = glm::vec4(brdf::sampleUniformCone(u, cosMax), brdf::uniformConePdf(cosMax));
  r.visible = glm::vec4(brdf::sampleGgxVisibleNormal(w, alpha, u), brdf::ggxSmithG1(w.z, alpha));
  r.anisotropic = glm::vec4(brdf::sampleGgxAnisotropicVisibleNormal(w, alphas, u), brdf::ggxAnisotropicG1(w, alphas));
  r.reflected = glm::vec4(brdf::reflectAbout(w, wi), brdf::powerHeuristic(c.u.z, c.u.w));
  r.pdfs = glm::vec4(brdf::ggxD(wi, alpha), brdf::ggxReflectionPdf(w, wi, alpha), brdf::ggxAnisotropicD(wi, alphas),
                     brdf::ggxAnisotropicReflectionPdf(w, wi, alphas));
  r.lambdas = glm::vec4(brdf::ggxLambda(w.z, alpha), brdf::ggxAnisotropicLambda(w, alphas), 0.0f, 0.0f);
  r.visibleAt = glm::vec4(brdf::ggxVisibleNormalAt(w, alphas, c.disk.x, glm::vec2(c.disk.y, c.disk.z)), 0.0f);
  return r;
}

// Which way component c of value k (its vec4's index in SamplingResult) is judged:
// the cone's direction and the sampled visible normals come through GLSL's cos and
// sin, all else through arithmetic that IEEE rounds alike in both languages.
enum class Judged { Exactly, ThroughCone, ThroughVisibleNormal };
Judged judged(int k, int c) {
  if (c == 3) return Judged::Exactly;  // the pdfs, G1 and the power heuristic beside them
  if (k == 7) return Judged::ThroughCone;
  if (k == 8 || k == 9) return Judged::ThroughVisibleNormal;
  return Judged::Exactly;
}

// The distance of b from a in units of the float spacing at max(|a|, scale): plain
// ulps for a value not much below its scale, and for a unit vector's component
// ulps of 1, so that a component near zero is not judged by its own tiny spacing.
// Infinite where one is NaN and the other is not.
double ulpsApart(float a, float b, float scale) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : HUGE_VAL;
  const float at = std::max(std::abs(a), scale);
  const double spacing = double(std::nextafter(at, std::numeric_limits<float>::infinity()) - at);
  return std::abs(double(a) - double(b)) / spacing;
}

// The scale of value k, component c: 1 for the unit vectors and the numbers in
// [0, 1] (cos, sin, G1, the power heuristic), none (the value's own ulps) for the
// densities and the Lambdas, which span decades.
float samplingScale(int k, int c) {
  if (k == 11 || k == 12) return 0.0f;
  if (c == 3 && (k == 6 || k == 7)) return 0.0f;  // cosineHemispherePdf, uniformConePdf
  return 1.0f;
}

std::vector<SamplingCase> samplingCases(int count) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<float> unit(0.0f, 0.99999994f);
  std::vector<SamplingCase> cases;
  cases.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    SamplingCase c;
    const glm::vec3 n = test::randomUnitVector(rng);
    const float angle = (unit(rng) * 2.0f - 1.0f) * 0.78539816f;
    // Now and then a normal at a pole, where frameAbout switches sides (-0 included).
    c.n = glm::vec4(i % 97 == 0 ? glm::vec3(0.0f, 0.0f, i % 2 ? -0.0f : 1.0f) : n, angle);
    const glm::vec3 tangent = test::randomUnitVector(rng);
    const float cosMax = 2.0f * unit(rng) - 1.0f;
    c.tangent = glm::vec4(tangent, cosMax);
    // wo above the surface (the visible normals need it), but grazing now and then;
    // the second direction anywhere; roughness from 0.001 (the smallest ggxAlpha) to 1.
    glm::vec3 w = test::randomUnitVector(rng);
    if (w.z < 0.0f) w.z = -w.z;
    if (i % 13 == 0) w = glm::normalize(glm::vec3(w.x, w.y, 1e-4f * w.z));
    const glm::vec3 wi = test::randomUnitVector(rng);
    const float a1 = unit(rng), a2 = unit(rng);
    c.w = glm::vec4(w, 0.001f + 0.999f * a1 * a1);
    c.wi = glm::vec4(wi, 0.001f + 0.999f * a2 * a2);
    const float u1 = unit(rng), u2 = unit(rng), p1 = unit(rng), p2 = unit(rng);
    // The power heuristic's pdfs: 0 (a delta, or a light that cannot be hit) at times.
    c.u = glm::vec4(u1, u2, i % 11 == 0 ? 0.0f : 10.0f * p1, i % 7 == 0 ? 0.0f : 10.0f * p2);
    const float phi = 2.0f * brdf::BRDF_PI * u2;
    c.disk = glm::vec4(std::sqrt(u1), std::cos(phi), std::sin(phi), 0.0f);
    cases.push_back(c);
  }
  return cases;
}

class SamplingText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(SamplingText);

// 65536 random cases, every routine of the text. Limits: the same bits wherever
// GLSL's cos and sin do not enter, the visible normal from the disk's point
// (ggxVisibleNormalAt) included: IEEE rounds +, -, *, / and sqrt alike everywhere,
// and a GPU compiler that would fuse a multiply and an add is stopped by the
// text's `precise` (llvmpipe, which these contexts run on, fuses none either way).
// GLSL's cos and sin are the driver's own, not libm's: the cone's direction, which
// multiplies them by sin theta, within 8 ulps of 1 (measured 0.5 on llvmpipe); the
// sampled visible normals within 2e-3 (measured 1.1e-4): where the disk's point
// nears its rim, the square roots of 1 - p1^2 and 1 - p1^2 - p2^2 magnify a
// last-bit change of cos or sin a thousandfold (the sampler's own conditioning: a
// last-bit change of u moves the sample as much there).
TEST_P(SamplingText, GlslAndCppAgree) {
  const std::vector<SamplingCase> cases = samplingCases(1 << 16);
  const std::vector<SamplingResult> gpu = test::runCases<SamplingResult>("test/sampling_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst[3] = {0.0, 0.0, 0.0};
  std::size_t worstCase = 0;
  int worstValue = 0, differ = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SamplingResult cpu = samplingOnCpu(cases[i]);
    const glm::vec4* a = &cpu.aboutS;
    const glm::vec4* b = &gpu[i].aboutS;
    for (int k = 0; k < kSamplingValues; ++k) {
      for (int c = 0; c < 4; ++c) {
        const int group = int(judged(k, c));
        const double e = ulpsApart(a[k][c], b[k][c], samplingScale(k, c));
        differ += e > 0.0 ? 1 : 0;
        if (e > worst[group]) {
          worst[group] = e;
          if (group == 0) worstCase = i, worstValue = k * 4 + c;
        }
      }
    }
  }
  std::printf("sampling: %zu cases, %d of %zu values differ; worst %.3g ulps without cos and sin (case %zu, value "
              "%d), %.3g ulps of 1 in the cone, %.3g (%.3g ulps of 1) in the visible normals\n",
              cases.size(), differ, cases.size() * kSamplingValues * 4, worst[0], worstCase, worstValue, worst[1],
              worst[2] * 0x1p-23, worst[2]);
  EXPECT_EQ(worst[0], 0.0) << "case " << worstCase << ", value " << worstValue;
  EXPECT_LE(worst[1], 8.0);
  EXPECT_LE(worst[2] * 0x1p-23, 2e-3);
}

struct ViewLayersCase {
  glm::vec4 n, sheen, stretch, film, f0, albedo;
};
struct ViewLayersResult {
  glm::vec4 anisotropyT, anisotropyB, iridescenceF;
};

std::vector<ViewLayersCase> viewLayersCases(int count) {
  std::mt19937 rng(20261208);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<ViewLayersCase> cases;
  cases.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    ViewLayersCase c;
    const glm::vec3 n = test::randomUnitVector(rng);
    const float nDotV = i % 17 == 0 ? 0.0f : unit(rng);
    c.n = glm::vec4(n, nDotV);
    const glm::vec3 sheenColor = test::draw3(unit, rng);
    c.sheen = glm::vec4(i % 3 == 0 ? glm::vec3(0.0f) : sheenColor, i % 3 == 0 ? 0.0f : 1.2f * unit(rng));
    // The stretch anywhere, absent (no uv gradient), or along n (nothing left to orient).
    glm::vec3 stretch = test::randomUnitVector(rng);
    if (i % 11 == 0) stretch = glm::vec3(0.0f);
    if (i % 13 == 0) stretch = n;
    c.stretch = glm::vec4(stretch, i % 4 == 0 ? 0.0f : unit(rng));
    const float share = i % 5 == 0 ? 0.0f : unit(rng), ior = 1.2f + 0.6f * unit(rng), nm = 1000.0f * unit(rng);
    c.film = glm::vec4(share, ior, nm, unit(rng));
    c.f0 = glm::vec4(0.08f * test::draw3(unit, rng), 0.0f);
    c.albedo = glm::vec4(test::draw3(unit, rng), 0.0f);
    cases.push_back(c);
  }
  return cases;
}

class ViewLayersText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(ViewLayersText);

// 16384 random cases. The sheen's scaling and the stretch's frame the same bits on
// both sides (IEEE arithmetic and sqrt only). The film's Fresnel within 1e-5 per
// unit of its largest phase, as tests/core/brdf_test.cpp holds iridescenceFresnel:
// the phase, up to 100 radians at 1000 nm, is rounded by some 1e-5 radians, which
// the driver's cosine passes on in full. Absolute, not relative: the Fresnel is a
// sum of terms of up to 1 that nearly cancel at times (a reflectance of 8e-5 came
// out 7e-4 off relative, 6e-8 absolute; measured 0.014 of the limit).
TEST_P(ViewLayersText, GlslAndCppAgree) {
  const std::vector<ViewLayersCase> cases = viewLayersCases(1 << 14);
  const std::vector<ViewLayersResult> gpu = test::runCases<ViewLayersResult>("test/view_layers_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  int exactDiffer = 0, stretched = 0, filmed = 0;
  double worstFilm = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ViewLayersCase& c = cases[i];
    const brdf::ViewLayers v =
        brdf::viewLayersOf(glm::vec3(c.n), c.n.w, c.sheen.w, glm::vec3(c.sheen), glm::vec3(c.stretch), c.stretch.w,
                           c.film.x, c.film.y, c.film.z, glm::vec3(c.f0), glm::vec3(c.albedo), c.film.w);
    const ViewLayersResult cpu{glm::vec4(v.anisotropyT, v.anisotropy), glm::vec4(v.anisotropyB, v.sheenScale),
                               glm::vec4(v.iridescenceF, v.sheenAlbedo)};
    exactDiffer += cpu.anisotropyT != gpu[i].anisotropyT || cpu.anisotropyB != gpu[i].anisotropyB ||
                           cpu.iridescenceF.w != gpu[i].iridescenceF.w
                       ? 1
                       : 0;
    stretched += v.anisotropy > 0.0f ? 1 : 0;
    filmed += v.iridescenceF != glm::vec3(0.0f) ? 1 : 0;
    const double opd = 2.0 * double(c.film.y) * double(c.film.z);  // nm, at most (cos theta2 <= 1)
    const double phase = 1.0 + 2.2084e6 * 2.0 * M_PI * 2.0 * opd * 1e-9;  // iridescenceSensitivity's second pair
    for (int k = 0; k < 3; ++k) {
      const double a = cpu.iridescenceF[k], b = gpu[i].iridescenceF[k];
      worstFilm = std::max(worstFilm, std::abs(a - b) / std::max(std::abs(a), 1.0) / (1e-5 * phase));
    }
  }
  std::printf("view layers: %zu cases (%d stretched, %d with a film), %d differ in the exact terms; film's Fresnel "
              "%.3g of its limit\n",
              cases.size(), stretched, filmed, exactDiffer, worstFilm);
  EXPECT_GT(stretched, int(cases.size()) / 2);
  EXPECT_GT(filmed, int(cases.size()) / 2);
  EXPECT_EQ(exactDiffer, 0);
  EXPECT_LE(worstFilm, 1.0);
}

struct SkyCase {
  glm::vec4 d, horizon, zenith, ground;
};

class SkyText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(SkyText);

// 65536 random directions (a third on the horizon's either side, where the gradient
// turns, and half of them near a random sun, many inside the disk's fading ring),
// random colours, the disk drawn or not. Limits: within 4 ulps of the largest of the
// value and 1: the text's mix and smoothstep are the driver's own on the GPU and
// glm's in C++, which may round otherwise (half the cases differ in a last bit on
// llvmpipe); sqrt and the sum are IEEE's. Measured 3 ulps on llvmpipe.
TEST_P(SkyText, GlslAndCppAgree) {
  std::mt19937 rng(20261208);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<SkyCase> cases;
  int ring = 0;
  for (int i = 0; i < (1 << 16); ++i) {
    const glm::vec3 sun = test::randomUnitVector(rng);
    glm::vec3 d = test::randomUnitVector(rng);
    if (i % 2) d = glm::normalize(sun + 0.03f * test::randomUnitVector(rng) * unit(rng));
    if (i % 3 == 0) d = glm::normalize(glm::vec3(d.x, (i % 2 ? 1e-4f : -1e-4f) * d.y, d.z));
    const float cosToSun = glm::dot(d, sun), disk = i % 4 == 0 ? 0.0f : 1.0f;
    ring += cosToSun > 0.9995f && cosToSun < 0.9998f ? 1 : 0;
    cases.push_back(SkyCase{glm::vec4(d, cosToSun), glm::vec4(test::draw3(unit, rng), disk),
                            glm::vec4(test::draw3(unit, rng), 0.0f), glm::vec4(test::draw3(unit, rng), 0.0f)});
  }
  const std::vector<glm::vec4> gpu = test::runCases<glm::vec4>("test/sky_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0;
  int differ = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SkyCase& c = cases[i];
    const glm::vec3 cpu = skytext::gradientSky(glm::vec3(c.d), glm::vec3(c.horizon), glm::vec3(c.zenith),
                                               glm::vec3(c.ground), c.d.w, c.horizon.w);
    differ += cpu != glm::vec3(gpu[i]) ? 1 : 0;
    for (int k = 0; k < 3; ++k) worst = std::max(worst, ulpsApart(cpu[k], gpu[i][k], 1.0f));
  }
  std::printf("sky: %zu cases (%d in the sun's ring), %d not the same bits, worst %.3g ulps of max(value, 1)\n",
              cases.size(), ring, differ, worst);
  EXPECT_GT(ring, int(cases.size()) / 20);
  EXPECT_LE(worst, 4.0);
}

class SpotConeText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(SpotConeText);

// 65536 cases: random cones (a tenth with the two cones one, a tenth a point light's
// cone below -1), cosines drawn across [-1, 1] and, for half of them, within or on
// the cones' edges, where the ramp starts and ends. Limit: the same bits. The text is
// comparisons, a subtraction, a division and a product, each IEEE's on both sides.
TEST_P(SpotConeText, GlslAndCppAgree) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::vec4> cases;
  int ramp = 0, edges = 0;
  for (int i = 0; i < (1 << 16); ++i) {
    float outer = std::cos(1.5707964f * unit(rng)), inner = std::cos(std::acos(outer) * unit(rng));
    if (i % 10 == 0) inner = outer;
    if (i % 10 == 1) outer = -3.0f, inner = -2.0f;
    float c = 2.0f * unit(rng) - 1.0f;
    if (i % 2) c = outer + (inner - outer) * unit(rng);
    if (i % 8 == 3) c = i % 16 == 3 ? outer : inner, ++edges;
    if (i % 8 == 5) c = std::nextafter(i % 16 == 5 ? outer : inner, 2.0f), ++edges;
    ramp += c > outer && c < inner ? 1 : 0;
    cases.push_back(glm::vec4(c, outer, inner, 0.0f));
  }
  const std::vector<glm::vec4> gpu = test::runCases<glm::vec4>("test/spot_cone_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  int differ = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4& c = cases[i];
    const float cpu = spottext::spotAttenuation(c.x, c.y, c.z);
    if (std::bit_cast<std::uint32_t>(cpu) != std::bit_cast<std::uint32_t>(gpu[i].x) && differ++ < 5)
      ADD_FAILURE() << "cos " << c.x << " outer " << c.y << " inner " << c.z << ": C++ " << cpu << ", GLSL " << gpu[i].x;
    EXPECT_TRUE(cpu >= 0.0f && cpu <= 1.0f);
  }
  std::printf("spot cone: %zu cases (%d on the ramp, %d on an edge), %d not the same bits\n", cases.size(), ramp, edges,
              differ);
  EXPECT_GT(ramp, int(cases.size()) / 4);
  EXPECT_EQ(differ, 0);
  // A point light's cone weighs every direction by exactly 1; outside the outer cone 0.
  for (float c : {-1.0f, -0.5f, 0.0f, 1.0f}) EXPECT_EQ(spottext::spotAttenuation(c, -3.0f, -2.0f), 1.0f);
  EXPECT_EQ(spottext::spotAttenuation(0.5f, 0.5f, 0.9f), 0.0f);
  EXPECT_EQ(spottext::spotAttenuation(0.75f, 0.5f, 1.0f), 0.25f);
}

struct AtmosphereCase {
  glm::vec4 heights, layers;
};
struct AtmosphereResult {
  glm::vec4 densities, extinction, bound, floorDensities, limb;
};

class AtmosphereText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(AtmosphereText);

// 65536 cases: altitudes from 1 km under the ground to 120 km (past the air's top),
// ranges of them (a tenth around the ozone tent's peak and edges), scale heights
// and tents around Earth's, sun radii across [0, 1]. Limits, relative to the larger
// of the value and 1e-30, in ulps per unit of the largest exponent |h / H| the case
// takes (plus one): GLSL's exp is the driver's, exp2 of x log2(e), whose rounding of
// the product moves the result by |x| ulps (measured: 59 ulps at x = 150, within 1
// per unit everywhere): the densities within 2, the extinction, a sum of three such
// products, within 4; the limb's pow within 16 ulps of 1 (the driver's pow).
TEST_P(AtmosphereText, GlslAndCppAgree) {
  std::mt19937 rng(20261210);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<AtmosphereCase> cases;
  for (int i = 0; i < (1 << 16); ++i) {
    const glm::vec4 layers(8000.0f * (0.5f + unit(rng)), 1200.0f * (0.5f + unit(rng)), 25000.0f * (0.8f + 0.4f * unit(rng)),
                           15000.0f * (0.8f + 0.4f * unit(rng)));
    float lo = 121000.0f * unit(rng) - 1000.0f, hi = lo + 20000.0f * unit(rng);
    if (i % 10 == 1) lo = layers.z - layers.w * unit(rng), hi = layers.z + layers.w * unit(rng);
    if (i % 10 == 2) lo = layers.z - layers.w, hi = lo;
    cases.push_back({glm::vec4(121000.0f * unit(rng) - 1000.0f, lo, hi, unit(rng)), layers});
  }
  const std::vector<AtmosphereResult> gpu = test::runCases<AtmosphereResult>("test/atmosphere_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worstDensity = 0.0, worstExtinction = 0.0, worstLimb = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const AtmosphereCase& c = cases[i];
    atmospheretext::Atmosphere a = atmospheretext::atmosphereOf(AtmosphereDesc{});
    a.rayleighScaleHeight = c.layers.x;
    a.mieScaleHeight = c.layers.y;
    a.ozoneCenter = c.layers.z;
    a.ozoneHalfWidth = c.layers.w;
    const glm::vec3 d = atmospheretext::atmosphereDensities(a, c.heights.x);
    const glm::vec3 e = atmospheretext::atmosphereExtinction(a, d);
    const glm::vec3 bound = atmospheretext::atmosphereDensityBound(a, c.heights.y, c.heights.z);
    const glm::vec3 floorDensities = atmospheretext::atmosphereDensityFloor(a, c.heights.y, c.heights.z);
    const glm::vec3 limb = atmospheretext::sunLimbDarkening(c.heights.w);
    const double exponent =
        1.0 + double(std::max({std::abs(c.heights.x), std::abs(c.heights.y), std::abs(c.heights.z)})) /
                  double(std::min(c.layers.x, c.layers.y));
    const auto apart = [&](float cpu, float glsl) {
      return ulpsApart(cpu, glsl, std::max(std::abs(cpu), 1e-30f)) / exponent;
    };
    for (int k = 0; k < 3; ++k) {
      worstDensity = std::max({worstDensity, apart(d[k], gpu[i].densities[k]), apart(bound[k], gpu[i].bound[k]),
                               apart(floorDensities[k], gpu[i].floorDensities[k])});
      worstExtinction = std::max(worstExtinction, apart(e[k], gpu[i].extinction[k]));
      worstLimb = std::max(worstLimb, ulpsApart(limb[k], gpu[i].limb[k], 1.0f));
    }
  }
  std::printf("atmosphere: %zu cases, densities within %.3g ulps a unit of exponent, extinction %.3g, limb within "
              "%.3g ulps of 1\n",
              cases.size(), worstDensity, worstExtinction, worstLimb);
  EXPECT_LE(worstDensity, 2.0);
  EXPECT_LE(worstExtinction, 4.0);
  EXPECT_LE(worstLimb, 16.0);
}

struct PhaseResult {
  glm::vec4 values, henyeyGreenstein, rayleigh;
};

class PhaseText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(PhaseText);

// 65536 cases: random cosines (a tenth at +-1), asymmetries g across (-0.999, 0.999)
// (a tenth below the uniform switch, 1e-3), uniform numbers (a tenth at 0 or just
// under 1). Limits: the densities within 4 ulps of the larger of value and 1 (a
// division and a root each, IEEE's on both sides: measured the same bits); the
// sampled cosines within 16 ulps of 1 (Rayleigh's goes through GLSL's pow, the
// driver's, not libm's); the sampled directions within 1e-6 radians of each other
// beyond what their cosines' difference explains (near the poles a cosine's last bit
// moves sin theta = sqrt(1 - cos^2) by many of its own ulps; the azimuth's cos and
// sin are the driver's too).
TEST_P(PhaseText, GlslAndCppAgree) {
  std::mt19937 rng(20261208);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::vec4> cases;
  for (int i = 0; i < (1 << 16); ++i) {
    float c = 2.0f * unit(rng) - 1.0f, g = 1.998f * unit(rng) - 0.999f, u = unit(rng), v = unit(rng);
    if (i % 10 == 1) c = i % 20 == 1 ? 1.0f : -1.0f;
    if (i % 10 == 2) g = 2e-3f * unit(rng) - 1e-3f;
    if (i % 10 == 3) u = i % 20 == 3 ? 0.0f : 0.99999994f;
    cases.push_back(glm::vec4(c, g, u, v));
  }
  const std::vector<PhaseResult> gpu = test::runCases<PhaseResult>("test/phase_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worstDensity = 0.0, worstCosine = 0.0, worstAngle = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4& c = cases[i];
    const glm::vec2 u(c.z, c.w);
    const glm::vec4 values(brdf::phaseHenyeyGreenstein(c.x, c.y), brdf::phaseRayleigh(c.x),
                           brdf::sampleHenyeyGreensteinCosine(c.z, c.y), brdf::sampleRayleighCosine(c.z));
    const glm::vec3 hg = brdf::samplePhaseHenyeyGreenstein(u, c.y), ray = brdf::samplePhaseRayleigh(u);
    for (int k = 0; k < 2; ++k) worstDensity = std::max(worstDensity, ulpsApart(values[k], gpu[i].values[k], 1.0f));
    for (int k = 2; k < 4; ++k) worstCosine = std::max(worstCosine, ulpsApart(values[k], gpu[i].values[k], 1.0f));
    // What the two cosines' difference explains: sin theta = sqrt(1 - cos^2) moves by
    // at most sqrt(2 |difference|).
    const glm::vec3 gpuHg(gpu[i].henyeyGreenstein), gpuRay(gpu[i].rayleigh);
    const double hgExplained = std::sqrt(2.0 * std::abs(double(hg.z) - double(gpuHg.z)));
    const double rayExplained = std::sqrt(2.0 * std::abs(double(ray.z) - double(gpuRay.z)));
    worstAngle = std::max({worstAngle, double(glm::length(hg - gpuHg)) - hgExplained,
                           double(glm::length(ray - gpuRay)) - rayExplained});
  }
  std::printf("phase: %zu cases, densities within %.3g ulps, sampled cosines within %.3g ulps of 1, directions within "
              "%.3g radians beyond what their cosines explain\n",
              cases.size(), worstDensity, worstCosine, worstAngle);
  EXPECT_LE(worstDensity, 4.0);
  EXPECT_LE(worstCosine, 16.0);
  EXPECT_LE(worstAngle, 1e-6);
}

struct TerrainLayersCase {
  glm::vec4 grassNear, grassFar, rockNear, rockFar, snow, slope;
};
struct TerrainLayersResult {
  glm::vec4 albedo, weights;
};

class TerrainLayersText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(TerrainLayersText);

// 65536 random layer colours, heights around the snow line and slopes around the
// rock's and the snow's edges. Limits: within 16 ulps of the largest of the value and
// 1: the text's smoothstep, mix and dot are the driver's own on the GPU and glm's in
// C++, which may round otherwise, and the weights' division by their sum and the
// blend pass a last-bit change of each smoothstep on (measured 7 ulps on llvmpipe;
// three in ten cases differ in some bit).
TEST_P(TerrainLayersText, GlslAndCppAgree) {
  std::mt19937 rng(20261209);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<TerrainLayersCase> cases;
  int mixed = 0;
  for (int i = 0; i < (1 << 16); ++i) {
    TerrainLayersCase c;
    c.grassNear = glm::vec4(test::draw3(unit, rng), 0.0f);
    c.grassFar = glm::vec4(test::draw3(unit, rng), 0.0f);
    c.rockNear = glm::vec4(test::draw3(unit, rng), 0.0f);
    c.rockFar = glm::vec4(test::draw3(unit, rng), 0.0f);
    const float height01 = i % 2 ? 0.5f + 0.3f * unit(rng) : 1.4f * unit(rng) - 0.2f;
    c.snow = glm::vec4(test::draw3(unit, rng), height01);
    c.slope = glm::vec4(i % 3 ? 0.2f + 0.5f * unit(rng) : unit(rng), 0.0f, 0.0f, 0.0f);
    cases.push_back(c);
  }
  const std::vector<TerrainLayersResult> gpu =
      test::runCases<TerrainLayersResult>("test/terrain_layers_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0;
  int differ = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TerrainLayersCase& c = cases[i];
    const terrain::TerrainLayers t =
        terrain::terrainLayersOf(glm::vec3(c.grassNear), glm::vec3(c.grassFar), glm::vec3(c.rockNear),
                                 glm::vec3(c.rockFar), glm::vec3(c.snow), c.snow.w, c.slope.x);
    const glm::vec3 rock = glm::vec3(c.rockNear) * glm::vec3(c.rockFar) * 2.0f;
    const glm::vec3 w = terrain::layerWeights(c.snow.w, c.slope.x, rock.x * 2.0f - 0.5f);
    mixed += w.x < 0.99f && w.y < 0.99f && w.z < 0.99f ? 1 : 0;
    const TerrainLayersResult cpu{glm::vec4(t.albedo, t.roughness), glm::vec4(w, t.specular)};
    differ += cpu.albedo != gpu[i].albedo || cpu.weights != gpu[i].weights ? 1 : 0;
    for (int k = 0; k < 4; ++k) {
      worst = std::max(worst, ulpsApart(cpu.albedo[k], gpu[i].albedo[k], 1.0f));
      worst = std::max(worst, ulpsApart(cpu.weights[k], gpu[i].weights[k], 1.0f));
    }
  }
  std::printf("terrain layers: %zu cases (%d with no layer above 0.99), %d not the same bits, worst %.3g ulps of "
              "max(value, 1)\n",
              cases.size(), mixed, differ, worst);
  EXPECT_GT(mixed, int(cases.size()) / 10);
  EXPECT_LE(worst, 16.0);
}

struct LayerTexelsCase {
  glm::dvec4 reflectance;  // x
  glm::vec4 texel[LAYER_SLOTS];
  glm::vec4 specular, coat, sheen, anisotropy, film, pad;  // as layer_texels_eval.comp's
};
static_assert(sizeof(LayerTexelsCase) == 320, "std430's layout of layer_texels_eval.comp's Case");
struct LayerTexelsResult {
  glm::vec4 specular, coat, sheen, anisotropy, film, f0;
};

class LayerTexelsText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(LayerTexelsText);

// 65536 random materials and texels, each slot present in half the cases (the
// present set as bits). Every operation is a product, an exact one (2x - 1), glm's
// mix as rt/math.glsl writes it, or a double one: the two compiles must give the
// same bits.
TEST_P(LayerTexelsText, GlslAndCppAgreeBitForBit) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<std::uint32_t> slots(0, (1u << LAYER_SLOTS) - 1u);
  std::vector<LayerTexelsCase> cases(1 << 16);
  for (LayerTexelsCase& c : cases) {
    const double ior = 1.0 + 3.0 * double(unit(rng));
    c.reflectance = glm::dvec4(((ior - 1.0) / (ior + 1.0)) * ((ior - 1.0) / (ior + 1.0)), 0.0, 0.0, 0.0);
    for (glm::vec4& t : c.texel) t = glm::vec4(test::draw3(unit, rng), unit(rng));
    c.specular = glm::vec4(test::draw3(unit, rng) * 8.0f, unit(rng));  // some tints past f0 = 1
    c.coat = glm::vec4(unit(rng), unit(rng), unit(rng), 10.0f * unit(rng));
    c.sheen = glm::vec4(test::draw3(unit, rng), unit(rng));
    c.anisotropy = glm::vec4(unit(rng) * 2.0f - 1.0f, unit(rng) * 2.0f - 1.0f, unit(rng), unit(rng));
    c.film = glm::vec4(1000.0f * unit(rng), 100.0f * unit(rng), 100.0f + 900.0f * unit(rng),
                       std::bit_cast<float>(slots(rng)));
  }
  const std::vector<LayerTexelsResult> gpu = test::runCases<LayerTexelsResult>("test/layer_texels_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  int differ = 0, clipped = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const LayerTexelsCase& c = cases[i];
    brdf::LayerValues v;
    v.specularColor = glm::vec3(c.specular);
    v.specularWeight = c.specular.w;
    v.clearcoat = c.coat.x;
    v.clearcoatRoughness = c.coat.y;
    v.transmission = c.coat.z;
    v.thickness = c.coat.w;
    v.sheenColor = glm::vec3(c.sheen);
    v.sheenRoughness = c.sheen.w;
    v.anisotropyDirection = glm::vec2(c.anisotropy);
    v.anisotropy = c.anisotropy.z;
    v.iridescence = c.anisotropy.w;
    v.iridescenceThickness = c.film.x;
    bool present[LAYER_SLOTS];
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(c.film.w);
    for (int k = 0; k < LAYER_SLOTS; ++k) present[k] = (bits & (1u << k)) != 0u;
    glm::vec4 texel[LAYER_SLOTS];
    std::copy(std::begin(c.texel), std::end(c.texel), texel);
    v = brdf::withLayerTexels(v, texel, present, glm::vec2(c.film.y, c.film.z));
    const glm::vec3 f0 = brdf::layerF0(c.reflectance.x, v.specularColor, v.specularWeight);
    clipped += glm::any(glm::greaterThan(glm::dvec3(c.reflectance.x) * glm::dvec3(v.specularColor), glm::dvec3(1.0)))
                   ? 1 : 0;
    const LayerTexelsResult cpu{glm::vec4(v.specularColor, v.specularWeight),
                                glm::vec4(v.clearcoat, v.clearcoatRoughness, v.transmission, v.thickness),
                                glm::vec4(v.sheenColor, v.sheenRoughness),
                                glm::vec4(v.anisotropyDirection, v.anisotropy, v.iridescence),
                                glm::vec4(v.iridescenceThickness, 0.0f, 0.0f, 0.0f), glm::vec4(f0, 0.0f)};
    const bool same = cpu.specular == gpu[i].specular && cpu.coat == gpu[i].coat && cpu.sheen == gpu[i].sheen &&
                      cpu.anisotropy == gpu[i].anisotropy && cpu.film == gpu[i].film && cpu.f0 == gpu[i].f0;
    differ += same ? 0 : 1;
  }
  std::printf("layer texels: %zu cases (%d with f0 clipped at 1), %d not the same bits\n", cases.size(), clipped,
              differ);
  EXPECT_GT(clipped, 0);
  EXPECT_EQ(differ, 0);
}

struct AnisotropyCase {
  glm::vec4 ns, dpdu, dpdv, direction;  // as oriented_anisotropy_eval.comp's
};

class OrientedAnisotropyText : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(OrientedAnisotropyText);

// 65536 random normals and uv gradients, a quarter of them degenerate: dP/du along
// the normal (nothing left of it in the tangent plane), zero, or infinite. The text
// is products, sums and square roots in glm's order (rtDot, rtCross), which IEEE
// rounds alike, and anisotropyDirection's turn by cos and sin, which are the driver's
// own on the GPU and libm's in C++ (a sixth of the cases differ in some bit). Limits:
// the same cases left unoriented, and within 32 ulps of 1 (measured 18 on llvmpipe,
// against 4 for the sky's text, which has no cos or sin).
TEST_P(OrientedAnisotropyText, GlslAndCppAgree) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<AnisotropyCase> cases(1 << 16);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::vec3 ns = test::randomUnitVector(rng);
    glm::vec3 dpdu = test::randomUnitVector(rng) * (0.01f + 10.0f * unit(rng));
    if (i % 16 == 1) dpdu = ns * 3.0f;
    if (i % 16 == 2) dpdu = glm::vec3(0.0f);
    if (i % 16 == 3) dpdu = glm::vec3(std::numeric_limits<float>::infinity(), 1.0f, 0.0f);
    const glm::vec3 dpdv = test::randomUnitVector(rng) * (0.01f + 10.0f * unit(rng));
    const float angle = 6.2831853f * unit(rng);
    cases[i] = AnisotropyCase{glm::vec4(ns, 1.5f * unit(rng)), glm::vec4(dpdu, angle - 3.1415927f),
                              glm::vec4(dpdv, 0.0f), glm::vec4(std::cos(angle), std::sin(angle), 0.0f, 0.0f)};
  }
  const std::vector<glm::vec4> gpu = test::runCases<glm::vec4>("test/oriented_anisotropy_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0;
  int differ = 0, unoriented = 0, unorientedDiffer = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const AnisotropyCase& c = cases[i];
    const glm::vec4 cpu = brdf::orientedAnisotropy(glm::vec2(c.direction), c.dpdu.w, c.ns.w, glm::vec3(c.ns),
                                                   glm::vec3(c.dpdu), glm::vec3(c.dpdv));
    differ += cpu != gpu[i] ? 1 : 0;
    unoriented += cpu == glm::vec4(0.0f) ? 1 : 0;
    unorientedDiffer += (cpu == glm::vec4(0.0f)) != (gpu[i] == glm::vec4(0.0f)) ? 1 : 0;
    for (int k = 0; k < 4; ++k) worst = std::max(worst, ulpsApart(cpu[k], gpu[i][k], 1.0f));
  }
  std::printf("oriented anisotropy: %zu cases (%d unoriented), %d not the same bits, worst %.3g ulps of max(value, 1)\n",
              cases.size(), unoriented, differ, worst);
  EXPECT_GE(unoriented, int(cases.size()) / 8);
  EXPECT_EQ(unorientedDiffer, 0);
  EXPECT_LE(worst, 32.0);
}

}  // namespace
