// One BRDF, two compilers: common/brdf.glsl run by the GPU's GLSL compiler in a
// compute shader and by the C++ build of the same text (core/brdf.h) agree over a grid
// of view and light angles, roughness, metallic and base colours (so f0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/gl_test.h"
#include "core/brdf.h"

using namespace engine;
using engine::test::GlTest;

namespace {

struct Case {
  glm::vec4 n, toEye, l, albedo, params, shininess;
  glm::vec4 dielectric;  // xyz dielectricF0, w dielectricF90
  glm::vec4 coat;        // clearcoat, clearcoat roughness, transmission, sheen albedo E
  glm::vec4 nc;          // the coat's normal
  glm::vec4 sheen;       // xyz sheen colour, w sheen roughness
  glm::vec4 anisotropy;  // xyz the stretch's direction (in the surface), w its strength
  glm::vec4 iridescence;  // xyz the film's Fresnel (as iridescenceFresnel would give it), w its share
};
struct Result {
  glm::vec4 metallicRoughness, classic, terms, fresnel, layered, hemisphere, transmitted, sheenTerms, anisotropic, film;
};

// glTF's layers, cycled through the grid: none (0.04, 1), ior 1.33 tinted at half
// weight, specular 0 (f0 0, f90 0), ior 2.5 under a smooth coat, a full rough coat
// on a tilted normal, a coat over a base with no specular, and two transmissive
// dielectrics (KHR_materials_transmission), one under a coat, and two sheens
// (KHR_materials_sheen; the albedo E as a table would give it), one over a
// transmissive base under a coat.
struct Layers {
  glm::vec3 f0;
  float f90, clearcoat, clearcoatRoughness;
  bool tilted;
  float transmission = 0.0f;
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f, sheenAlbedo = 0.0f;
  float anisotropy = 0.0f;
  float iridescence = 0.0f;
};
const Layers kLayers[] = {{glm::vec3(0.04f), 1.0f, 0.0f, 0.0f, false},
                          {glm::vec3(0.02f, 0.01f, 0.005f), 0.5f, 0.0f, 0.0f, false},
                          {glm::vec3(0.0f), 0.0f, 0.0f, 0.0f, false},
                          {glm::vec3(0.18f), 1.0f, 0.5f, 0.05f, false},
                          {glm::vec3(0.04f), 1.0f, 1.0f, 0.7f, true},
                          {glm::vec3(0.0f), 0.0f, 0.8f, 0.3f, true},
                          {glm::vec3(0.04f), 1.0f, 0.0f, 0.0f, false, 0.7f},
                          {glm::vec3(0.03f, 0.04f, 0.05f), 0.8f, 0.6f, 0.2f, true, 1.0f},
                          {glm::vec3(0.04f), 1.0f, 0.0f, 0.0f, false, 0.0f, glm::vec3(1.0f, 0.5f, 0.25f), 0.5f, 0.3f},
                          {glm::vec3(0.04f), 1.0f, 0.5f, 0.1f, true, 0.5f, glm::vec3(0.2f, 0.9f, 0.4f), 0.05f, 0.9f},
                          {glm::vec3(0.04f), 1.0f, 0.0f, 0.0f, false, 0.0f, glm::vec3(0.0f), 0.0f, 0.0f, 0.5f},
                          {glm::vec3(0.1f), 1.0f, 0.4f, 0.3f, true, 0.0f, glm::vec3(0.5f), 0.4f, 0.2f, 1.0f},
                          {glm::vec3(0.04f), 1.0f, 0.0f, 0.0f, false, 0.0f, glm::vec3(0.0f), 0.0f, 0.0f, 0.0f, 1.0f},
                          {glm::vec3(0.04f), 1.0f, 0.5f, 0.2f, true, 0.4f, glm::vec3(0.3f), 0.5f, 0.3f, 0.5f, 0.6f}};

glm::vec3 direction(float thetaDegrees, float phiDegrees) {
  const float t = glm::radians(thetaDegrees), p = glm::radians(phiDegrees);
  return {std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p)};
}

// View and light from head-on to 89 degrees (grazing), on the same and opposite
// sides; roughness 0 to 1; dielectric to metal; dark, saturated and white colours.
std::vector<Case> grid() {
  std::vector<Case> cases;
  const glm::vec3 n = glm::normalize(glm::vec3(0.1f, 1.0f, -0.2f));
  const glm::vec3 albedos[] = {{0.02f, 0.02f, 0.02f}, {0.9f, 0.3f, 0.05f}, {1.0f, 1.0f, 1.0f}};
  for (const float thetaV : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
    for (const float thetaL : {0.0f, 20.0f, 45.0f, 75.0f, 89.0f}) {
      for (const float phi : {0.0f, 90.0f, 180.0f}) {
        for (int r = 0; r <= 10; ++r) {
          for (const float metallic : {0.0f, 0.5f, 1.0f}) {
            for (const glm::vec3& albedo : albedos) {
              // Tilted with the normal, so no component is exactly 0 or 1.
              const glm::vec3 axisFix = glm::normalize(n);
              const glm::vec3 v = glm::normalize(direction(thetaV, 10.0f) + (axisFix - glm::vec3(0, 1, 0)));
              const glm::vec3 l = glm::normalize(direction(thetaL, 10.0f + phi) + (axisFix - glm::vec3(0, 1, 0)));
              const Layers& layers = kLayers[cases.size() % std::size(kLayers)];
              const glm::vec3 nc = layers.tilted ? glm::normalize(n + glm::vec3(0.15f, 0.0f, 0.1f)) : n;
              // A direction in the surface, turned with phi so the stretch meets the
              // light from several sides.
              const glm::vec3 stretch =
                  glm::normalize(glm::cross(n, glm::vec3(std::cos(glm::radians(phi + 20.0f)), 0.0f,
                                                         std::sin(glm::radians(phi + 20.0f)))));
              cases.push_back(Case{glm::vec4(n, 0), glm::vec4(v, 0), glm::vec4(l, 0), glm::vec4(albedo, 0),
                                   glm::vec4(metallic, float(r) / 10.0f, 0.9f, 0.5f), glm::vec4(8.0f + 12.0f * float(r)),
                                   glm::vec4(layers.f0, layers.f90),
                                   glm::vec4(layers.clearcoat, layers.clearcoatRoughness, layers.transmission,
                                             layers.sheenAlbedo),
                                   glm::vec4(nc, 0.0f), glm::vec4(layers.sheenColor, layers.sheenRoughness),
                                   glm::vec4(stretch, layers.anisotropy),
                                   glm::vec4(0.3f, 0.6f, 0.2f, layers.iridescence)});
            }
          }
        }
      }
    }
  }
  return cases;
}

Result onCpu(const Case& c) {
  const glm::vec3 n(c.n), v(c.toEye), l(c.l), albedo(c.albedo);
  const float metallic = c.params.x, roughness = c.params.y;
  const glm::vec3 h = glm::normalize(l + v);
  const float alpha = brdf::ggxAlpha(roughness);
  Result r;
  r.metallicRoughness = glm::vec4(brdf::metallicRoughnessBrdf(n, v, l, albedo, metallic, roughness), 0.0f);
  r.classic = glm::vec4(brdf::classicReflected(n, v, l, albedo, c.params.z, c.params.w, c.shininess.x), 0.0f);
  r.terms = glm::vec4(brdf::ggxDistribution(n, h, alpha),
                      brdf::smithVisibility(std::max(glm::dot(n, l), 0.0f), std::max(glm::dot(n, v), 1e-4f), alpha),
                      alpha, 0.0f);
  r.fresnel = glm::vec4(brdf::schlickFresnel(brdf::metallicF0(albedo, metallic), std::max(glm::dot(v, h), 0.0f)), 0.0f);
  const glm::vec3 f0(c.dielectric), nc(c.nc);
  const glm::vec3 sheenColor(c.sheen);
  r.layered = glm::vec4(brdf::layeredBrdf(n, v, l, albedo, metallic, roughness, f0, c.dielectric.w, nc, c.coat.x, c.coat.y,
                                          c.coat.z, sheenColor, c.sheen.w, brdf::sheenScaling(sheenColor, c.coat.w),
                                          glm::vec3(c.anisotropy), glm::cross(n, glm::vec3(c.anisotropy)), c.anisotropy.w,
                                          glm::vec3(c.iridescence), c.iridescence.w),
                        0.0f);
  r.hemisphere = glm::vec4(brdf::hemisphereAmbient(albedo, metallic, roughness, f0, std::max(glm::dot(nc, v), 1e-4f),
                                                   c.coat.x, c.coat.y, c.coat.z, sheenColor, c.coat.w,
                                                   glm::vec3(c.iridescence), c.iridescence.w),
                           0.0f);
  // The sheen's terms at the case's angles, with the material roughness as the
  // sheen's (all of 0..1), wherever the light is above the surface.
  const float nDotL = std::max(glm::dot(n, l), 1e-4f), nDotV = std::max(glm::dot(n, v), 1e-4f);
  const float sheenAlpha = brdf::sheenAlpha(roughness);
  r.sheenTerms = glm::vec4(brdf::charlieDistribution(n, h, sheenAlpha), brdf::sheenVisibility(nDotL, nDotV, sheenAlpha),
                           brdf::sheenLambda(nDotV, sheenAlpha), brdf::sheenBrdf(n, v, l, roughness));
  // Anisotropy's helpers: the bent reflection normal at the case's strength (or 0.7)
  // and the turned direction.
  const float strength = c.anisotropy.w > 0.0f ? c.anisotropy.w : 0.7f;
  r.anisotropic = glm::vec4(brdf::anisotropicReflectionNormal(n, v, glm::cross(n, glm::vec3(c.anisotropy)), strength, roughness),
                            brdf::anisotropyDirection(glm::vec2(0.6f, 0.8f), 3.0f * roughness - 1.0f).x);
  // The thin film's Fresnel at the case's view angle: film index 1.2 to 2.2 (so
  // above and below the base's), 0 to 1000 nm (the fade below 30 nm included).
  r.film = glm::vec4(brdf::iridescenceFresnel(1.0f, 1.2f + 2.0f * c.params.w * roughness, nDotV, 1000.0f * roughness,
                                              brdf::metallicF0(albedo, metallic)),
                     0.0f);
  // The transmission helpers: the light back through the surface, through a volume
  // of the roughness-derived length with the albedo as its attenuation colour.
  const glm::vec3 reflected = brdf::schlickFresnel90(f0, c.dielectric.w, std::max(glm::dot(n, v), 1e-4f));
  r.transmitted = glm::vec4(brdf::transmittedShare(albedo, metallic, c.coat.z, reflected) *
                                brdf::volumeAttenuation(albedo, 0.5f, 0.1f + roughness),
                            brdf::transmissionRoughness(roughness, 1.0f + c.params.w * c.coat.z));
  return r;
}

// The Charlie distribution raises sin^2 of the half-vector angle to the power
// 1 / (2 alpha), 500 at the smoothest sheen: a power p multiplies its input's
// relative rounding by p, and the GPU's compiler rounds the cross product under it
// differently in the last bit (fused multiply-adds). So the values that hold a
// Charlie term (sheenTerms' distribution and BRDF, the layered BRDF of a sheen case)
// are held to 1e-5 per unit of 1 + p: the same agreement of the inputs, not a
// looser one of the formula.
// The thin film's Fresnel (value 9) is a sum of cosines of the optical phase, up to
// 120 radians for a 1000 nm film of index 2.2: a float argument that large is
// rounded by some 1e-5 radians, which the cosine passes on in full. Its values are
// held to 1e-5 per unit of that largest argument, for the same reason.
double charlieCondition(const Case& c, int value, int component) {
  const bool sheenTerm = value == 7 && (component == 0 || component == 3);
  const bool layeredSheen = value == 4 && glm::vec3(c.sheen) != glm::vec3(0.0f);
  if (sheenTerm) return 1.0 + 0.5 / double(brdf::sheenAlpha(c.params.y));
  if (layeredSheen) return 1.0 + 0.5 / double(brdf::sheenAlpha(c.sheen.w));
  if (value == 9) {
    const double roughness = c.params.y, ior = 1.2 + 2.0 * c.params.w * roughness, thickness = 1000.0 * roughness;
    const double opd = 2.0 * ior * thickness;  // nm, at most (cos theta2 <= 1)
    return 1.0 + 2.2084e6 * 2.0 * M_PI * 2.0 * opd * 1e-9;  // the second pair's largest argument
  }
  return 1.0;
}

class Brdf : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(Brdf);

// Relative agreement 1e-5 (about 80 float ulps: room for the GPU compiler's own
// rounding of sqrt, pow and division, none for a different formula). Values below
// 1e-6 are compared absolutely: there a relative error says nothing.
TEST_P(Brdf, GlslAndCppAgree) {
  const std::vector<Case> cases = grid();
  const std::vector<Result> gpu = test::runCases<Result>("test/brdf_eval.comp", cases);
  ASSERT_EQ(gpu.size(), cases.size());

  double worst = 0.0;
  std::size_t worstCase = 0;
  int worstValue = 0, nonZero = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Result cpu = onCpu(cases[i]);
    const glm::vec4* a = &cpu.metallicRoughness;
    const glm::vec4* b = &gpu[i].metallicRoughness;
    for (int k = 0; k < 10; ++k) {
      for (int c = 0; c < (k >= 6 && k <= 8 ? 4 : 3); ++c) {  // the .w of transmitted, sheenTerms, anisotropic
        const double x = a[k][c], y = b[k][c];
        ASSERT_TRUE(std::isfinite(y)) << "case " << i << " value " << k;
        if (std::abs(x) > 1e-6) ++nonZero;
        const double error = std::abs(x - y) / std::max(std::abs(x), 1e-6) / charlieCondition(cases[i], k, c);
        if (error > worst) {
          worst = error;
          worstCase = i;
          worstValue = k * 4 + c;
        }
      }
    }
  }
  EXPECT_GT(nonZero, int(cases.size()));  // the grid is not all zeros
  // Without layers the C++ layered BRDF is the plain one to the last bit: the tracers
  // call it for every material, and those without the extensions render as before.
  // (The rasterizer builds the layered variant only for materials that have them.)
  for (std::size_t i = 0; i < cases.size(); i += std::size(kLayers)) {
    const Result cpu = onCpu(cases[i]);
    ASSERT_EQ(cpu.layered, cpu.metallicRoughness) << "case " << i;
  }
  EXPECT_LE(worst, 1e-5) << "case " << worstCase << " of " << cases.size() << ", value " << worstValue;
  std::printf("brdf: %zu cases, worst relative difference %.3g (case %zu, value %d)\n", cases.size(), worst, worstCase,
              worstValue);
}

}  // namespace
