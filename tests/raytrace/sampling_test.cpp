// Every sampling routine of the path tracer against the pdf it claims, by a
// chi-square test (pbrt-v4's bsdfs_test.cpp: 80 x 160 cells, a million samples,
// alpha = 0.01 over the whole suite by Sidak's correction), and the energy the
// metallic-roughness BSDF reflects at every roughness and angle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>

#include "chi_square.h"
#include "raytrace/bsdf.h"
#include "raytrace/path_lights.h"
#include "raytrace/sampling.h"

namespace rt = engine::rt;

namespace {

// Every chi-square case of this file; the Sidak correction keeps the chance that any
// of them fails by bad luck at 1 %.
constexpr int kChiSquareCases = 1 + 3 + 12 + 8 + 3 + 2 + 4;
const double kSignificance = chi2::sidak(0.01, kChiSquareCases);

void expectPasses(const chi2::Result& r) {
  EXPECT_GT(r.degreesOfFreedom, 0) << r.message;
  EXPECT_GT(r.pValue, kSignificance) << r.message;
}

glm::vec3 fromTheta(float thetaDegrees) {
  const float t = glm::radians(thetaDegrees);
  return {std::sin(t), 0.0f, std::cos(t)};
}

TEST(ChiSquare, CosineHemisphere) {
  expectPasses(chi2::test(
      [](glm::vec2 u, glm::vec3* w) {
        *w = rt::sampleCosineHemisphere(u);
        return true;
      },
      [](const glm::vec3& w) { return double(rt::cosineHemispherePdf(w.z)); }));
}

// How many floats lie between a and b (both finite, of the same sign or zero).
std::int64_t ulpsBetween(float a, float b) {
  auto ordered = [](float f) {
    std::int32_t i;
    std::memcpy(&i, &f, sizeof i);
    return i < 0 ? -std::int64_t(i & 0x7fffffff) : std::int64_t(i);
  };
  return std::abs(ordered(a) - ordered(b));
}

// The concentric map's cosine and sine over its whole range |a| <= pi / 4: 2^24 evenly
// spaced angles and every float within 2^20 ulps of 0 and of either end, against
// double's sin and cos rounded to float.
TEST(SamplingTest, QuarterSinCosIsWithinThreeUlps) {
  const float quarter = std::nextafter(float(std::numbers::pi / 4), 0.0f);
  std::int64_t worst = 0;
  float worstAngle = 0.0f;
  auto check = [&](float a) {
    const glm::vec2 cs = rt::cosSinQuarter(a);
    const std::int64_t e = std::max(ulpsBetween(cs.x, float(std::cos(double(a)))),
                                    ulpsBetween(cs.y, float(std::sin(double(a)))));
    if (e > worst) worst = e, worstAngle = a;
  };
  constexpr int kEven = 1 << 24;
  for (int i = 0; i <= kEven; ++i) check(-quarter + 2.0f * quarter * (float(i) / float(kEven)));
  for (float a = 0.0f, b = -0.0f; ulpsBetween(a, 0.0f) < (1 << 20); a = std::nextafter(a, 1.0f), b = -a) {
    check(a), check(b);
  }
  float a = quarter;
  for (int i = 0; i < (1 << 20); ++i, a = std::nextafter(a, 0.0f)) check(a), check(-a);
  EXPECT_LE(worst, 3) << "at " << worstAngle;
}

TEST(ChiSquare, UniformCone) {
  for (const float cosMax : {0.98f, 0.5f, -0.4f}) {
    SCOPED_TRACE(cosMax);
    expectPasses(chi2::test(
        [cosMax](glm::vec2 u, glm::vec3* w) {
          *w = rt::sampleUniformCone(u, cosMax);
          return true;
        },
        [cosMax](const glm::vec3& w) { return w.z >= cosMax ? double(rt::uniformConePdf(cosMax)) : 0.0; }));
  }
}

TEST(ChiSquare, GgxVisibleNormalReflection) {
  for (const float alpha : {0.1f, 0.3f, 0.6f, 1.0f}) {
    for (const float theta : {0.0f, 45.0f, 80.0f}) {
      SCOPED_TRACE(testing::Message() << "alpha " << alpha << ", theta_o " << theta);
      const glm::vec3 wo = fromTheta(theta);
      expectPasses(chi2::test(
          [&](glm::vec2 u, glm::vec3* w) {
            *w = rt::reflectAbout(wo, rt::sampleGgxVisibleNormal(wo, alpha, u));
            return w->z > 0.0f;
          },
          [&](const glm::vec3& w) { return double(rt::ggxReflectionPdf(wo, w, alpha)); }));
    }
  }
}

engine::rt::HitMaterial material(glm::vec3 albedo, float metallic, float roughness) {
  engine::rt::HitMaterial m;
  m.albedo = albedo;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

void expectBsdfSamplesItsPdf(const rt::Bsdf& bsdf) {
  std::mt19937 lobes(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  expectPasses(chi2::test(
      [&](glm::vec2 u, glm::vec3* w) {
        const auto s = bsdf.sample(u, uniform(lobes));
        if (!s.drawn || s.delta) return false;
        *w = s.wi;
        return true;
      },
      [&](const glm::vec3& w) { return double(bsdf.pdf(w)); }));
}

TEST(ChiSquare, MetallicRoughnessBsdf) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (const float metallic : {0.0f, 1.0f}) {
    for (const float roughness : {0.35f, 0.8f}) {
      for (const float theta : {10.0f, 70.0f}) {
        SCOPED_TRACE(testing::Message() << "metallic " << metallic << ", roughness " << roughness << ", theta_o " << theta);
        expectBsdfSamplesItsPdf(rt::Bsdf::metallicRoughness(material(glm::vec3(0.9f, 0.6f, 0.3f), metallic, roughness), n,
                                                            fromTheta(theta)));
      }
    }
  }
}

// glTF's layers (KHR_materials_ior, _specular, _clearcoat): the coat's GGX lobe joins
// the mixture, and the base's lobes keep their share of the rest.
engine::rt::HitMaterial layered(float metallic, float roughness, glm::vec3 f0, float f90, float coat, float coatRoughness) {
  engine::rt::HitMaterial m = material(glm::vec3(0.9f, 0.6f, 0.3f), metallic, roughness);
  m.dielectricF0 = f0;
  m.dielectricF90 = f90;
  m.clearcoat = coat;
  m.clearcoatRoughness = coatRoughness;
  return m;
}

TEST(ChiSquare, LayeredBsdf) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const engine::rt::HitMaterial cases[] = {
      layered(1.0f, 0.6f, glm::vec3(0.04f), 1.0f, 1.0f, 0.15f),          // a coated metal
      layered(0.0f, 0.5f, glm::vec3(0.0f), 0.0f, 0.5f, 0.5f),            // no specular under a half coat
      layered(0.0f, 0.3f, glm::vec3(0.02f, 0.015f, 0.01f), 0.6f, 0.0f, 0.0f),  // ior 1.33, tinted, weight 0.6
      layered(0.0f, 0.9f, glm::vec3(0.04f), 1.0f, 0.3f, 0.05f),          // a thin smooth coat on a rough base
  };
  for (const auto& m : cases) {
    for (const float theta : {65.0f}) {
      SCOPED_TRACE(testing::Message() << "coat " << m.clearcoat << ", f90 " << m.dielectricF90 << ", theta_o " << theta);
      expectBsdfSamplesItsPdf(rt::Bsdf::metallicRoughness(m, n, fromTheta(theta)));
    }
  }
}

// KHR_materials_sheen joins the cosine-weighted share of the mixture: over a metal,
// which alone would give that share nothing, and over a coated dielectric.
TEST(ChiSquare, SheenBsdf) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  engine::rt::HitMaterial metal = layered(1.0f, 0.2f, glm::vec3(0.04f), 1.0f, 0.0f, 0.0f);
  metal.sheenColor = glm::vec3(0.8f, 0.7f, 0.9f);
  metal.sheenRoughness = 0.3f;
  engine::rt::HitMaterial coated = layered(0.0f, 0.5f, glm::vec3(0.04f), 1.0f, 0.5f, 0.2f);
  coated.sheenColor = glm::vec3(1.0f);
  coated.sheenRoughness = 0.8f;
  for (const auto& m : {metal, coated}) {
    for (const float theta : {30.0f, 75.0f}) {
      SCOPED_TRACE(testing::Message() << "metallic " << m.metallic << ", theta_o " << theta);
      expectBsdfSamplesItsPdf(rt::Bsdf::metallicRoughness(m, n, fromTheta(theta)));
    }
  }
}

// KHR_materials_anisotropy: the base's visible normals drawn from the stretched GGX
// in a frame whose x follows the stretch (here a direction in the surface that is
// neither of the default frame's axes), at half and full strength.
TEST(ChiSquare, AnisotropicBsdf) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (const float strength : {0.5f, 1.0f}) {
    engine::rt::HitMaterial m = material(glm::vec3(0.9f, 0.6f, 0.3f), 0.3f, 0.3f);
    m.anisotropy = strength;
    m.anisotropyT = glm::normalize(glm::vec3(0.6f, 0.8f, 0.1f));
    for (const float theta : {30.0f, 70.0f}) {
      SCOPED_TRACE(testing::Message() << "strength " << strength << ", theta_o " << theta);
      expectBsdfSamplesItsPdf(rt::Bsdf::metallicRoughness(m, n, fromTheta(theta)));
    }
  }
}

TEST(ChiSquare, ClassicBsdfWithoutItsMirror) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (const float reflection : {0.0f, 0.5f, 0.8f}) {
    SCOPED_TRACE(reflection);
    engine::rt::HitMaterial m = material(glm::vec3(0.7f), 0.0f, 0.5f);
    m.diffuse = 0.9f;
    m.specular = 0.3f;
    m.shininess = 20.0f;
    m.reflection = reflection;
    expectBsdfSamplesItsPdf(rt::Bsdf::classic(m, n, fromTheta(40.0f)));
  }
}

// The environment's importance sampling, on a sky with a small bright sun and a
// dark ground: the directions it draws follow the pdf it reports. Tested in a frame
// whose +z is the world's +y (the environment's pole).
TEST(ChiSquare, EnvironmentLight) {
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.6f, -0.5f));
  const rt::EnvironmentLight::RadianceFn skies[] = {
      [sun](const glm::vec3& d) {
        return glm::vec3(d.y > 0.0f ? 1.0f : 0.1f) + glm::vec3(200.0f) * float(glm::dot(d, sun) > 0.995f);
      },
      [](const glm::vec3& d) { return glm::vec3(0.5f + 0.5f * d.x, 0.2f, 1.0f - d.y * d.y); },
  };
  for (const auto& sky : skies) {
    const rt::EnvironmentLight env(sky, glm::ivec2(128, 64));
    const auto toWorld = [](const glm::vec3& w) { return glm::vec3(w.x, w.z, w.y); };
    expectPasses(chi2::test(
        [&](glm::vec2 u, glm::vec3* w) {
          float pdf = 0.0f;
          const glm::vec3 d = env.sample(u, &pdf);
          *w = glm::vec3(d.x, d.z, d.y);
          return pdf > 0.0f;
        },
        [&](const glm::vec3& w) { return double(env.pdf(toWorld(w))); }));
  }
}

// The share of light from wo that the BSDF reflects, estimated with 16k samples.
double directionalAlbedo(const engine::rt::HitMaterial& m, float cosTheta, std::mt19937& rng) {
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const glm::vec3 wo(std::sqrt(1.0f - cosTheta * cosTheta), 0.0f, cosTheta);
  const rt::Bsdf bsdf = rt::Bsdf::metallicRoughness(m, glm::vec3(0.0f, 0.0f, 1.0f), wo);
  double sum = 0.0;
  constexpr int kSamples = 16384;
  for (int i = 0; i < kSamples; ++i) {
    if (const auto s = bsdf.sample(glm::vec2(uniform(rng), uniform(rng)), uniform(rng)); s.drawn) sum += double(s.weight.x);
  }
  return sum / kSamples;
}

double directionalAlbedo(float metallic, float roughness, float cosTheta, std::mt19937& rng) {
  return directionalAlbedo(material(glm::vec3(1.0f), metallic, roughness), cosTheta, rng);
}

// GGX (a white metal: the specular lobe alone, Fresnel 1) never reflects more than
// it receives, at any roughness or angle; 1 % for the estimate's noise. Single
// scattering loses energy at high roughness instead (the floor of 0.2 catches a lobe
// that lost its samples).
TEST(Energy, GgxAlbedoNeverExceedsOne) {
  std::mt19937 rng(11);
  for (int r = 0; r <= 20; ++r) {
    for (int a = 0; a <= 20; ++a) {
      const float roughness = float(r) / 20.0f, cosTheta = std::max(0.02f, float(a) / 20.0f);
      const double albedo = directionalAlbedo(1.0f, roughness, cosTheta, rng);
      EXPECT_LE(albedo, 1.01) << "roughness " << roughness << ", cos " << cosTheta;
      EXPECT_GT(albedo, 0.2) << "roughness " << roughness << ", cos " << cosTheta;
    }
  }
}

// The dielectric of glTF's model (the spec's appendix B, the Khronos Sample Viewer's
// and the rasterizer's: Lambert weighted by 1 - F(V.H) under GGX) is not energy
// conserving: seen at grazing angles a smooth white dielectric reflects up to 1.89
// times the light it receives (measured: roughness 0, cos 0.01), because the
// diffuse lobe's weight uses the half vector of each light direction, not the
// specular lobe's actual albedo. Both renderers share that model, so the path tracer
// inherits it. Averaged over the hemisphere of views it stays within 4.2 % of 1
// (measured 1.0419 at roughness 0, falling to 0.976 at roughness 1); this pins that
// figure, so that a change which makes it worse fails.
TEST(Energy, GltfDielectricGainsAtMostFourPercentOverTheHemisphere) {
  std::mt19937 rng(13);
  for (int r = 0; r <= 10; ++r) {
    const float roughness = float(r) / 10.0f;
    double hemispherical = 0.0, weights = 0.0;
    for (int a = 0; a < 50; ++a) {
      const float cosTheta = (float(a) + 0.5f) / 50.0f;
      hemispherical += directionalAlbedo(0.0f, roughness, cosTheta, rng) * cosTheta;
      weights += cosTheta;
    }
    EXPECT_LE(hemispherical / weights, 1.045) << "roughness " << roughness;
    EXPECT_GT(hemispherical / weights, 0.9) << "roughness " << roughness;
  }
}

// A clear coat over a white metal (the base reflects everything it receives) takes
// from the base what its own Fresnel reflects: the stack never reflects more than
// 1 % over what it receives, at any roughness of either layer or any angle.
TEST(Energy, ClearCoatNeverAddsEnergy) {
  std::mt19937 rng(17);
  for (const float base : {0.0f, 0.5f, 1.0f}) {
    for (int r = 0; r <= 10; r += 2) {
      for (int a = 0; a <= 10; ++a) {
        const float coatRoughness = float(r) / 10.0f, cosTheta = std::max(0.02f, float(a) / 10.0f);
        engine::rt::HitMaterial m = material(glm::vec3(1.0f), 1.0f, base);
        m.clearcoat = 1.0f;
        m.clearcoatRoughness = coatRoughness;
        EXPECT_LE(directionalAlbedo(m, cosTheta, rng), 1.01)
            << "base roughness " << base << ", coat roughness " << coatRoughness << ", cos " << cosTheta;
      }
    }
  }
}

// KHR_materials_anisotropy: a white metal stretched to any strength, at any
// roughness, seen from any angle and azimuth across the stretch, never reflects more
// than it receives (1 % for the estimate's noise), as the isotropic lobe does.
TEST(Energy, AnisotropicGgxNeverExceedsOne) {
  std::mt19937 rng(29);
  for (const float strength : {0.3f, 0.7f, 1.0f}) {
    for (int r = 0; r <= 10; r += 2) {
      for (const float cosTheta : {0.05f, 0.3f, 0.7f, 1.0f}) {
        for (const float azimuth : {0.0f, 0.8f, 1.57f}) {
          engine::rt::HitMaterial m = material(glm::vec3(1.0f), 1.0f, float(r) / 10.0f);
          m.anisotropy = strength;
          m.anisotropyT = glm::vec3(std::cos(azimuth), std::sin(azimuth), 0.0f);
          EXPECT_LE(directionalAlbedo(m, cosTheta, rng), 1.01)
              << "strength " << strength << ", roughness " << r / 10.0 << ", cos " << cosTheta << ", azimuth " << azimuth;
        }
      }
    }
  }
}

// KHR_materials_iridescence: a thin film over a white metal (thickness 0 to 1000 nm,
// film index below and above the base's) reflects a Fresnel of at most 1 in every
// channel (measured up to 1.0002: the Gaussian fit of the eye's sensitivity and its
// turn to RGB overshoot that little; 0.1 % allowed), so the stack never reflects
// more than it receives (1 % for the estimate's noise).
TEST(Energy, IridescentFilmNeverAddsEnergy) {
  std::mt19937 rng(31);
  for (const float thickness : {0.0f, 150.0f, 400.0f, 1000.0f}) {
    for (const float ior : {1.2f, 1.8f}) {
      for (const float cosTheta : {0.05f, 0.4f, 1.0f}) {
        engine::rt::HitMaterial m = material(glm::vec3(1.0f), 1.0f, 0.4f);
        m.iridescence = 1.0f;
        m.iridescenceIor = ior;
        m.iridescenceThickness = thickness;
        const glm::vec3 film = m.iridescenceFresnelAt(cosTheta);
        EXPECT_LE(std::max({film.x, film.y, film.z}), 1.001f) << thickness << " nm, ior " << ior << ", cos " << cosTheta;
        EXPECT_LE(directionalAlbedo(m, cosTheta, rng), 1.01) << thickness << " nm, ior " << ior << ", cos " << cosTheta;
      }
    }
  }
}

// The mean of f cos / pdf over `samples` draws from wo, and its standard error.
struct AlbedoEstimate {
  double mean = 0.0, standardError = 0.0;
};
AlbedoEstimate sampledAlbedo(const engine::rt::HitMaterial& m, float cosTheta, int samples, std::mt19937& rng) {
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const glm::vec3 wo(std::sqrt(1.0f - cosTheta * cosTheta), 0.0f, cosTheta);
  const rt::Bsdf bsdf = rt::Bsdf::metallicRoughness(m, glm::vec3(0.0f, 0.0f, 1.0f), wo);
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < samples; ++i) {
    const auto s = bsdf.sample(glm::vec2(uniform(rng), uniform(rng)), uniform(rng));
    const double w = s.drawn ? double(s.weight.x) : 0.0;
    sum += w;
    squares += w * w;
  }
  const double mean = sum / samples;
  return {mean, std::sqrt(std::max(squares / samples - mean * mean, 0.0) / samples)};
}

// KHR_materials_sheen, by albedo scaling: over a white metal (GGX alone, which never
// gains energy) a white sheen takes from the base what it reflects itself, so the
// stack never reflects more than it receives, at every roughness of either and every
// angle down to N.V 0.05 (below it glTF's sheen alone exceeds 1: core/sheen_table.h).
// Over a black base with neither diffuse nor specular the path tracer's sampled
// albedo is the sheen table's E, which checks the table, the lobe's weights and its
// sampling together. The limits: 4 standard errors of the estimate (its noise, which
// a smooth sheen at grazing views makes large), plus 0.5 % (the table's quadrature
// and its bilinear filter).
TEST(Energy, SheenNeverAddsEnergyAndReflectsItsTable) {
  std::mt19937 rng(23);
  constexpr int kSamples = 65536;
  for (const float sheenRoughness : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    for (const float cosTheta : {0.05f, 0.1f, 0.3f, 0.6f, 1.0f}) {
      const std::string where = "sheen roughness " + std::to_string(sheenRoughness) + ", cos " + std::to_string(cosTheta);
      for (const float base : {0.1f, 0.5f, 1.0f}) {
        engine::rt::HitMaterial m = material(glm::vec3(1.0f), 1.0f, base);
        m.sheenColor = glm::vec3(1.0f);
        m.sheenRoughness = sheenRoughness;
        const AlbedoEstimate a = sampledAlbedo(m, cosTheta, kSamples, rng);
        EXPECT_LE(a.mean, 1.005 + 4.0 * a.standardError) << where << ", base roughness " << base;
      }
      engine::rt::HitMaterial black = material(glm::vec3(0.0f), 0.0f, 0.5f);
      black.dielectricF0 = glm::vec3(0.0f);
      black.dielectricF90 = 0.0f;
      black.sheenColor = glm::vec3(1.0f);
      black.sheenRoughness = sheenRoughness;
      const double e = black.sheenAlbedo(cosTheta);
      const AlbedoEstimate a = sampledAlbedo(black, cosTheta, kSamples, rng);
      EXPECT_NEAR(a.mean, e, 4.0 * a.standardError + 0.005 * std::max(e, 0.1)) << where;
    }
  }
}

// KHR_materials_transmission: white glass (no diffuse left) reflects F and passes
// 1 - F of what it receives, each lobe losing only GGX's masking, so the sum of the
// two never exceeds what comes in, at any roughness or angle, through a thin wall,
// into a volume or out of one (where total internal reflection keeps it all); smooth
// glass loses nothing (the floor, at 3 %, catches a lobe whose weight was dropped).
TEST(Energy, TransmissionNeitherAddsNorLosesLightInSmoothGlass) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const float thickness : {0.0f, 1.0f}) {
    for (const bool entering : {true, false}) {
      for (int r = 0; r <= 10; r += 2) {
        for (int a = 1; a <= 10; ++a) {
          const float roughness = float(r) / 10.0f, cosTheta = float(a) / 10.0f;
          engine::rt::HitMaterial m = material(glm::vec3(1.0f), 0.0f, roughness);
          m.transmission = 1.0f;
          m.thickness = thickness;
          const glm::vec3 wo(std::sqrt(1.0f - cosTheta * cosTheta), 0.0f, cosTheta);
          const rt::Bsdf bsdf = rt::Bsdf::metallicRoughness(m, glm::vec3(0.0f, 0.0f, 1.0f), wo, entering);
          double sum = 0.0;
          constexpr int kSamples = 16384;
          for (int i = 0; i < kSamples; ++i) {
            const auto s = bsdf.sample(glm::vec2(uniform(rng), uniform(rng)), uniform(rng));
            if (s.drawn) sum += double(s.weight.x);
          }
          const double albedo = sum / kSamples;
          const std::string where = "thickness " + std::to_string(thickness) + (entering ? ", entering" : ", leaving") +
                                    ", roughness " + std::to_string(roughness) + ", cos " + std::to_string(cosTheta);
          EXPECT_LE(albedo, 1.01) << where;
          if (r == 0) {
            EXPECT_GT(albedo, 0.97) << where;
          }
        }
      }
    }
  }
}

TEST(Distribution2D, PdfIntegratesToOneAndFollowsTheWeights) {
  const std::vector<float> weights = {0, 1, 2, 3, 0, 0, 0, 10};
  const rt::Distribution2D d(weights, 4, 2);
  double integral = 0.0;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) integral += d.pdf(glm::vec2((x + 0.5f) / 4.0f, (y + 0.5f) / 2.0f)) / 8.0;
  }
  EXPECT_NEAR(integral, 1.0, 1e-6);
  EXPECT_FLOAT_EQ(d.pdf(glm::vec2(0.9f, 0.9f)), 10.0f / 16.0f * 8.0f);
  // Never a zero-weight cell, however u falls.
  for (int i = 0; i <= 1000; ++i) {
    for (const float v : {0.0f, 0.37f, 0.375f, 0.999999f}) {
      float pdf = 0.0f;
      const glm::vec2 p = d.sample(glm::vec2(float(i) / 1001.0f, v), &pdf);
      ASSERT_GT(pdf, 0.0f) << p.x << " " << p.y;
      ASSERT_GT(d.pdf(p), 0.0f);
    }
  }
}

}  // namespace
