// The path tracer's tracked media (raytrace/media.h): the atmosphere's layers, a
// height fog and boxes, against closed forms and quadratures: the columns of air,
// the trackers' transmittance and free flights, the single-scattered sky, a
// volumetric white furnace, and an area light seen through a fog.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include "core/phase.h"
#include "raytrace/integrator.h"
#include "raytrace/media.h"
#include "raytrace/rng.h"
#include "../support/quadrature.h"
#include "test_scenes.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

engine::AtmosphereDesc earth() {
  engine::AtmosphereDesc a;
  a.enabled = true;
  return a;
}

engine::FogDesc heightFog(glm::vec3 scattering, glm::vec3 absorption, float falloff, float g = 0.0f) {
  engine::FogDesc fog;
  fog.enabled = true;
  fog.model = engine::FogModel::Volumetric;
  fog.scattering = scattering;
  fog.absorption = absorption;
  fog.heightFalloff = falloff;
  fog.anisotropy = g;
  return fog;
}

engine::MediumDesc box(glm::dvec3 min, glm::dvec3 max, glm::vec3 scattering, glm::vec3 absorption) {
  engine::MediumDesc m;
  m.min = min;
  m.max = max;
  m.scattering = scattering;
  m.absorption = absorption;
  return m;
}

// The optical depth of `channel` along o + t d over [0, length], by quadrature of the
// extinction the trackers see, cut at the given points (kinks and steps).
double opticalDepth(const rt::Media& media, glm::dvec3 o, glm::dvec3 d, double length, int channel,
                    std::vector<double> cuts = {}) {
  cuts.push_back(0.0);
  cuts.push_back(length);
  std::sort(cuts.begin(), cuts.end());
  const auto extinction = [&](double t) { return double(media.at(o + t * d, channel).extinction); };
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = std::clamp(cuts[i], 0.0, length), b = std::clamp(cuts[i + 1], 0.0, length);
    if (!(b > a)) continue;
    // To 1e-8 of a rough sum: the densities are float, rounded to 6e-8, so a much
    // finer tolerance would halve the pieces to the depth limit everywhere.
    double rough = 0.0;
    for (int k = 0; k < 64; ++k) rough += extinction(a + (k + 0.5) * (b - a) / 64.0) * (b - a) / 64.0;
    sum += engine::test::integrate(extinction, a, b, 1e-8 * std::max(rough, 1e-9), 24);
  }
  return sum;
}

// Where a ray from o along d leaves the sphere of `radius` about the planet's centre.
double exitDistance(glm::dvec3 o, glm::dvec3 d, double radius, double planetRadius) {
  const glm::dvec3 oc = o - glm::dvec3(0.0, -planetRadius, 0.0);
  const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
  return -b + std::sqrt(b * b - c);
}

// Straight up from the ground the layers' columns are closed forms: Rayleigh's and
// Mie's sigma H (1 - exp(-top / H)), ozone's tent sigma times its half width. The
// quadrature of the extinction the trackers see against them: within 1e-6 (the
// text's densities are float).
TEST(Media, AtmosphereColumnsAreTheLayersClosedForms) {
  const engine::AtmosphereDesc a = earth();
  const std::optional<rt::Media> media = rt::Media::of(engine::FogDesc{}, a, {});
  ASSERT_TRUE(media);
  EXPECT_TRUE(media->tracked());
  const double top = a.thickness;
  for (int c = 0; c < 3; ++c) {
    const double rayleigh = a.rayleighScattering[c] * a.rayleighScaleHeight * (1.0 - std::exp(-top / a.rayleighScaleHeight));
    const double mie =
        (a.mieScattering[c] + a.mieAbsorption[c]) * a.mieScaleHeight * (1.0 - std::exp(-top / a.mieScaleHeight));
    const double ozone = double(a.ozoneAbsorption[c]) * a.ozoneHalfWidth;
    const double column = opticalDepth(*media, {0, 0, 0}, {0, 1, 0}, top, c, {10e3, 25e3, 40e3});
    std::printf("channel %d: column %.6f, closed form %.6f\n", c, column, rayleigh + mie + ozone);
    EXPECT_NEAR(column / (rayleigh + mie + ozone), 1.0, 1e-6) << "channel " << c;
  }
}

struct TrackedRay {
  const char* name;
  glm::dvec3 o, d;
  double length;
};

// Ratio tracking's transmittance, the mean of 200000 estimates, against exp of the
// quadrature's optical depth, per channel, along rays through Earth's air (level at
// the ground, rising at 5 and 30 degrees, down from 3 km and level at 20 km), through
// a height fog and through a box: within 4 standard errors, and 1e-7 of the
// transmittance (the fog's and the box's are closed forms, exact but for the
// densities' float rounding). Where the transmittance is above 1 %, the air's errors
// are under 4e-3 of it (measured 3e-3 at most, level at the ground), so the test
// sees a mistake of 1.6 %. (The tracker's noise, not the quadrature, sets that
// figure: the optical depth it estimates is the closed form's to 1e-6,
// AtmosphereColumnsAreTheLayersClosedForms.)
TEST(Media, RatioTrackingIsTheQuadraturesTransmittance) {
  const double r = earth().planetRadius, top = r + earth().thickness;
  const auto rising = [](double degrees) {
    return glm::dvec3(std::cos(glm::radians(degrees)), std::sin(glm::radians(degrees)), 0.0);
  };
  const glm::dvec3 down = glm::normalize(glm::dvec3(1.0, -0.05, 0.0));
  struct Case {
    std::optional<rt::Media> media;
    TrackedRay ray;
    std::vector<double> cuts;
  };
  std::vector<Case> cases;
  const auto air = rt::Media::of(engine::FogDesc{}, earth(), {});
  cases.push_back({air, {"air, level", {0, 2, 0}, {1, 0, 0}, exitDistance({0, 2, 0}, {1, 0, 0}, top, r)}, {}});
  cases.push_back({air, {"air, 5 degrees", {0, 2, 0}, rising(5), exitDistance({0, 2, 0}, rising(5), top, r)}, {}});
  cases.push_back({air, {"air, 30 degrees", {0, 2, 0}, rising(30), exitDistance({0, 2, 0}, rising(30), top, r)}, {}});
  cases.push_back({air, {"air, down from 3 km", {0, 3000, 0}, down, 50e3}, {}});
  cases.push_back({air, {"air, level at 20 km", {0, 20e3, 0}, {0, 0, 1}, 600e3}, {}});
  const engine::FogDesc fog = heightFog(glm::vec3(0.005f, 0.01f, 0.02f), glm::vec3(0.002f), 0.1f);
  cases.push_back({rt::Media::of(fog, {}, {}), {"height fog, rising", {0, -5, 0}, rising(10), 2000.0}, {}});
  cases.push_back({rt::Media::of(fog, {}, {}), {"height fog, sinking", {0, 40, 0}, -rising(20), 150.0}, {}});
  const engine::MediumDesc b = box({1, -1, -1}, {3, 1, 1}, glm::vec3(0.3f, 0.6f, 0.9f), glm::vec3(0.2f));
  cases.push_back({rt::Media::of(engine::FogDesc{}, {}, {b}), {"box", {0, 0, 0}, rising(15), 10.0},
                   {1.0 / std::cos(glm::radians(15.0)), 1.0 / std::sin(glm::radians(15.0))}});
  rt::Pcg32 rng(2026u, 12u);
  const int n = 200000;
  for (const Case& k : cases) {
    ASSERT_TRUE(k.media) << k.ray.name;
    for (int c = 0; c < 3; ++c) {
      const double truth = std::exp(-opticalDepth(*k.media, k.ray.o, k.ray.d, k.ray.length, c, k.cuts));
      double sum = 0.0, squares = 0.0;
      for (int i = 0; i < n; ++i) {
        const double t = k.media->transmittance(k.ray.o, k.ray.d, k.ray.length, c, rng);
        sum += t;
        squares += t * t;
      }
      const double mean = sum / n, error = std::sqrt(std::max(squares / n - mean * mean, 0.0) / (n - 1));
      std::printf("%s, channel %d: %.6f +- %.2g, quadrature %.6f\n", k.ray.name, c, mean, error, truth);
      EXPECT_NEAR(mean, truth, 4.0 * error + 1e-7 * truth) << k.ray.name << ", channel " << c;
      if (truth > 0.01) {
        EXPECT_LT(error, 4e-3 * truth) << k.ray.name << ", channel " << c;
      }
    }
  }
}

// The planet's ground stops light: a ray down into it lets nothing through, and a
// ray from above toward the ground ends there.
TEST(Media, TheGroundStopsWhatReachesIt) {
  const auto air = rt::Media::of(engine::FogDesc{}, earth(), {});
  rt::Pcg32 rng(7u, 1u);
  const glm::dvec3 o(0, 1000, 0), d = glm::normalize(glm::dvec3(1, -0.1, 0));
  EXPECT_EQ(air->transmittance(o, d, std::numeric_limits<double>::infinity(), 1, rng), 0.0f);
  int ground = 0;
  for (int i = 0; i < 1000; ++i) {
    const rt::Media::Flight f = air->track(o, d, std::numeric_limits<double>::infinity(), 0, rng);
    if (f.event == rt::Media::Event::Ground) {
      ++ground;
      EXPECT_NEAR(glm::length(o + f.distance * d - glm::dvec3(0, -earth().planetRadius, 0)), earth().planetRadius, 1e-3);
    }
  }
  EXPECT_GT(ground, 800);  // about 10 km of air at the ground, red: 94 % get there
}

// Delta tracking's free flights: the share of flights that collide before s is
// 1 - T(s), and their weights (the albedo where they collide) sum to the integral
// of sigma_s T over [0, s]; 400000 flights per channel along a rising ray through
// Earth's air and a height fog, within 4 standard errors.
TEST(Media, DeltaTrackingCollidesWhereTheExtinctionSays) {
  const engine::FogDesc fog = heightFog(glm::vec3(0.02f, 0.01f, 0.0f), glm::vec3(0.005f, 0.0f, 0.01f), 0.02f);
  struct Case {
    const char* name;
    std::optional<rt::Media> media;
    glm::dvec3 o, d;
    double s;
  };
  const std::vector<Case> cases = {
      {"air", rt::Media::of(engine::FogDesc{}, earth(), {}), {0, 10, 0}, glm::normalize(glm::dvec3(1, 0.02, 0)), 80e3},
      {"height fog", rt::Media::of(fog, {}, {}), {0, -20, 0}, glm::normalize(glm::dvec3(1, 0.2, 0)), 150.0}};
  rt::Pcg32 rng(99u, 3u);
  const int n = 400000;
  for (const Case& k : cases) {
    for (int c = 0; c < 3; ++c) {
      // The truth on a fine grid: tau by the trapezoid rule, the weight's integral by
      // Simpson's over the same points.
      const int steps = 20000;
      const double h = k.s / steps;
      double tau = 0.0, scattered = 0.0, previous = k.media->at(k.o, c).extinction;
      std::vector<double> f(steps + 1);
      f[0] = double(k.media->at(k.o, c).scattering);
      for (int i = 1; i <= steps; ++i) {
        const rt::Media::Coefficients here = k.media->at(k.o + (i * h) * k.d, c);
        tau += 0.5 * h * (previous + here.extinction);
        previous = here.extinction;
        f[std::size_t(i)] = double(here.scattering) * std::exp(-tau);
      }
      for (int i = 0; i + 2 <= steps; i += 2) scattered += h / 3.0 * (f[i] + 4.0 * f[i + 1] + f[i + 2]);
      const double collide = 1.0 - std::exp(-tau);
      int collided = 0;
      double weights = 0.0, squares = 0.0;
      for (int i = 0; i < n; ++i) {
        const rt::Media::Flight flight = k.media->track(k.o, k.d, k.s, c, rng);
        if (flight.event == rt::Media::Event::Through) continue;
        ++collided;
        weights += flight.weight;
        squares += double(flight.weight) * flight.weight;
      }
      const double share = double(collided) / n, shareError = std::sqrt(collide * (1.0 - collide) / n);
      const double mean = weights / n, meanError = std::sqrt(std::max(squares / n - mean * mean, 0.0) / (n - 1));
      std::printf("%s, channel %d: collided %.5f (truth %.5f), weights %.5f (truth %.5f)\n", k.name, c, share, collide,
                  mean, scattered);
      EXPECT_NEAR(share, collide, 4.0 * shareError + 1e-6) << k.name << ", channel " << c;
      EXPECT_NEAR(mean, scattered, 4.0 * meanError + 1e-5 * scattered + 1e-9) << k.name << ", channel " << c;
    }
  }
}

// The volumetric white furnace with tracked media: inside a closed black sphere that
// emits 1, a height fog (2.5 per metre at y = 0, thinning e-fold every 2 m) and a box
// of haze, all scattering and absorbing nothing (albedo 1, g 0.6 and 0): radiance 1
// everywhere. 16 x 16 at 256 spp: the mean within 0.025 per channel; each pixel's
// mean over its channels within 10 % (a path carries one channel, drawn at its
// start, so a pixel's channels differ by which ones its paths drew; their mean does
// not).
TEST(Media, TrackedWhiteFurnaceIsOne) {
  rt::RtScene scene = emptyScene(lookAt({0.1, -0.2, 0.3}, {1, 0.5, 2}, 90.0));
  MaterialDesc wall = classic(glm::vec3(0.0f), 0.0f, 0.0f);
  wall.emission = glm::vec3(1.0f);
  scene.addSphere({0, 0, 0}, 2.0, scene.addMaterial(wall));
  scene.setFog(heightFog(glm::vec3(2.5f), glm::vec3(0.0f), 0.5f, 0.6f));
  scene.setMedia({box({-1, -1, -1}, {1, 0.5, 1.5}, glm::vec3(1.5f, 1.0f, 3.0f), glm::vec3(0.0f))});
  const rt::RenderResult r = rt::Integrator(scene, pathSettings(16, 16, 256, 256)).render();
  const glm::dvec3 mean = meanOf(r.image);
  std::printf("tracked furnace: mean %.4f %.4f %.4f\n", mean.x, mean.y, mean.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.025);
  for (const glm::vec3& p : r.image.pixels) ASSERT_NEAR((p.x + p.y + p.z) / 3.0f, 1.0, 0.1);
}

// An area light 5 m away, seen through a medium that only absorbs, by channel (0.1,
// 0.15, 0.2 per metre): each pixel shows exp(-absorption * distance) of its radiance,
// through a homogeneous fog (drawn over the three channels at once) and through a
// box of the same fog (tracked). 16 x 16 at 1024 spp against the closed forms at the
// pixel centres: within 2.5 % per channel, 4 standard errors of the box's noise (a
// path carries one channel: a third of the 262144 paths each, reaching the light
// with probability 0.35 in blue: 0.45 % from that, 0.3 % from how many drew it). A
// light counted at the transmittance of its distance only when the flight got past
// it would show exp(-2 absorption * distance): 40 to 60 % too dark.
TEST(Media, AnAreaLightThroughAnAbsorbingFogIsBeerLambert) {
  const glm::vec3 absorption(0.1f, 0.15f, 0.2f);
  for (bool tracked : {false, true}) {
    rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 40.0));
    LightDesc light;
    light.type = LightType::Area;
    light.position = {0, 0, 5};
    light.edgeU = {0, 40, 0};
    light.edgeV = {40, 0, 0};  // u x v faces the camera
    light.intensity = 1.0f;
    light.color = glm::vec3(1.0f);
    scene.addLight(light);
    if (tracked) {
      scene.setMedia({box({-50, -50, -1}, {50, 50, 10}, glm::vec3(0.0f), absorption)});
    } else {
      scene.setFog(heightFog(glm::vec3(0.0f), absorption, 0.0f));
    }
    const int side = 16;
    const rt::RenderResult r = rt::Integrator(scene, pathSettings(side, side, 1024)).render();
    const double tanHalf = std::tan(20.0 * kPi / 180.0);
    glm::dvec3 expected(0.0);
    for (int y = 0; y < side; ++y) {
      for (int x = 0; x < side; ++x) {
        const double px = (2.0 * (x + 0.5) / side - 1.0) * tanHalf, py = (2.0 * (y + 0.5) / side - 1.0) * tanHalf;
        const double distance = 5.0 * std::sqrt(1.0 + px * px + py * py);
        for (int c = 0; c < 3; ++c) expected[c] += std::exp(-double(absorption[c]) * distance);
      }
    }
    expected /= double(side * side);
    const glm::dvec3 mean = meanOf(r.image);
    std::printf("%s: mean %.4f %.4f %.4f, closed form %.4f %.4f %.4f\n", tracked ? "box" : "fog", mean.x, mean.y,
                mean.z, expected.x, expected.y, expected.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c] / expected[c], 1.0, 0.025) << (tracked ? "box" : "fog") << c;
  }
}

// The sky at the zenith in single scattering (one scattering in the air, a black
// ground), with a sun 30 degrees up: the radiance along the ray is the integral over
// t of T(0, t) (sigma_R p_R + sigma_M p_HG) pi I T(t, sun) (the engine's sun of
// intensity I lights a white Lambert surface facing it to I). The air is ten times
// Earth's, so that most paths scatter (in Earth's, 94 % of the red ones leave
// unscattered, and the noise would need five times the paths). The mean of 60000
// paths along the zenith against a nested quadrature, per channel: within 4 standard
// errors, each under 3 % of the value.
TEST(Media, SingleScatteredZenithIsItsIntegral) {
  engine::AtmosphereDesc a = earth();
  a.groundAlbedo = glm::vec3(0.0f);
  a.rayleighScattering *= 10.0f;
  a.mieScattering *= 10.0f;
  a.mieAbsorption *= 10.0f;
  a.ozoneAbsorption *= 10.0f;
  rt::RtScene scene = emptyScene(lookAt({0, 1, 0}, {0, 2, 0.001}, 40.0));
  scene.setAtmosphere(a);
  LightDesc sun;
  sun.type = LightType::Sun;
  const double elevation = glm::radians(30.0);
  sun.direction = glm::dvec3(0.0, std::sin(elevation), std::cos(elevation));
  sun.intensity = 10.0f;
  scene.addLight(sun);
  const auto media = rt::Media::of(engine::FogDesc{}, a, {});
  const double top = a.planetRadius + a.thickness;
  const glm::dvec3 o(0, 1, 0), up(0, 1, 0), toSun(sun.direction);
  // Between the light's directions of travel: from the sun (-toSun), then down the
  // zenith to the camera (-up).
  const float cosine = float(glm::dot(-toSun, -up));
  rt::RenderSettings settings = pathSettings(1, 1, 1);
  settings.mediumScatterings = 1;
  rt::Integrator integrator(scene, settings);
  const int n = 60000;
  for (int c = 0; c < 3; ++c) {
    const double column = exitDistance(o, up, top, a.planetRadius);
    const auto integrand = [&](double t) {
      const glm::dvec3 p = o + t * up;
      const double h = glm::length(p - glm::dvec3(0, -a.planetRadius, 0)) - a.planetRadius;
      const double rayleigh = a.rayleighScattering[c] * std::exp(-h / a.rayleighScaleHeight);
      const double mie = a.mieScattering[c] * std::exp(-h / a.mieScaleHeight);
      const double phase = rayleigh * engine::brdf::phaseRayleigh(cosine) +
                           mie * engine::brdf::phaseHenyeyGreenstein(cosine, a.mieAnisotropy);
      const double toSunDepth = opticalDepth(*media, p, toSun, exitDistance(p, toSun, top, a.planetRadius), c);
      return std::exp(-opticalDepth(*media, o, up, t, c)) * phase * kPi * sun.intensity * std::exp(-toSunDepth);
    };
    const double truth = engine::test::integrate(integrand, 0.0, column, 1e-7, 18);
    double sum = 0.0, squares = 0.0;
    for (int i = 0; i < n; ++i) {
      const double v = integrator.traceRay(rt::Ray<double>{o, up, 1e30}, std::uint64_t(i) * 3 + 1)[c];
      sum += v;
      squares += v * v;
    }
    const double mean = sum / n, error = std::sqrt(std::max(squares / n - mean * mean, 0.0) / (n - 1));
    std::printf("zenith, channel %d: %.5f +- %.5f against the quadrature's %.5f\n", c, mean, error, truth);
    EXPECT_NEAR(mean, truth, 4.0 * error) << "channel " << c;
    EXPECT_LT(error, 0.03 * truth) << "channel " << c;
  }
}

}  // namespace
