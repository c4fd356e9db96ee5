// The path tracer's participating medium (raytrace/medium.h, a volumetric fog)
// against answers known in closed form or by quadrature: a volumetric white furnace,
// transmittance through an absorbing medium per colour channel, single scattering
// of a point light against a quadrature of its integral, and images that depend on
// the seed alone, not on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/phase.h"
#include "raytrace/describe.h"
#include "raytrace/integrator.h"
#include "raytrace/medium.h"
#include "raytrace/rng.h"
#include "../support/quadrature.h"
#include "test_scenes.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

engine::FogDesc volumetric(glm::vec3 scattering, glm::vec3 absorption, float g = 0.0f) {
  return volumetricFog(scattering, absorption, g);
}

// The volumetric white furnace: inside a closed black sphere that emits 1, a medium
// that scatters and never absorbs (albedo 1, forward scattering g = 0.6, a mean free
// path of a fifth of the radius) keeps radiance 1 everywhere: every bounce, the free
// flights' weights, the phase function's sampling and its MIS with the (black)
// environment must be right. 16 x 16 at 256 spp, mean within 0.025 (the pbrt furnace's
// limit), each pixel within 10 %.
TEST(Medium, VolumetricWhiteFurnaceIsOne) {
  rt::RtScene scene = emptyScene(lookAt({0.1, -0.2, 0.3}, {1, 0.5, 2}, 90.0));
  MaterialDesc wall = classic(glm::vec3(0.0f), 0.0f, 0.0f);
  wall.emission = glm::vec3(1.0f);
  scene.addSphere({0, 0, 0}, 2.0, scene.addMaterial(wall));
  scene.setFog(volumetric(glm::vec3(2.5f), glm::vec3(0.0f), 0.6f));
  const rt::RenderResult r = rt::Integrator(scene, pathSettings(16, 16, 256, 256)).render();
  const glm::dvec3 mean = meanOf(r.image);
  std::printf("volumetric furnace: mean %.4f %.4f %.4f\n", mean.x, mean.y, mean.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.025);
  for (const glm::vec3& p : r.image.pixels) ASSERT_NEAR(p.x, 1.0, 0.1);
}

// An emitting black wall 5 m away through a medium that only absorbs, by channel
// (0.1, 0.4, 1 per metre): a pixel shows exp(-absorption * distance) of it, the
// distance along its ray. The image's mean against the mean of the closed forms at
// the rays' pixel centres, 32 x 32 at 512 spp: within 1 % per channel (4 standard
// errors of the channel sampling's noise; measured -0.2 %).
TEST(Medium, AbsorptionIsBeerLambertPerChannel) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 40.0));
  MaterialDesc wall = classic(glm::vec3(0.0f), 0.0f, 0.0f);
  wall.emission = glm::vec3(1.0f);
  scene.addPlane({0, 0, 5}, {0, 0, -1}, scene.addMaterial(wall));
  const glm::vec3 absorption(0.1f, 0.4f, 1.0f);
  scene.setFog(volumetric(glm::vec3(0.0f), absorption));
  const int side = 32;
  const rt::RenderResult r = rt::Integrator(scene, pathSettings(side, side, 512)).render();
  const glm::dvec3 expected = beerLambertMean(side, 40.0, 5.0, absorption);
  const glm::dvec3 mean = meanOf(r.image);
  std::printf("absorption: mean %.4f %.4f %.4f, closed form %.4f %.4f %.4f\n", mean.x, mean.y, mean.z, expected.x,
              expected.y, expected.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c] / expected[c], 1.0, 0.01) << "channel " << c;
}

// Single scattering (one bounce at most: maxDepth 0) of a point light of intensity I
// with 1/d^2 falloff, 1 m off a ray through a medium of scattering 0.3 and absorption
// 0.1 per metre, g = 0.5, seen by a camera on the ray: the radiance along it is the
// integral over t of sigma_s T(t) p(theta(t)) pi I T(r(t)) / r(t)^2 (the engine's
// point light gives pi I / d^2: a white Lambert surface facing it reflects I). The
// mean of 400000 paths along that exact ray against a quadrature of the integral:
// within 4 standard errors.
TEST(Medium, SingleScatteringOfAPointLightIsItsIntegral) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 40.0));
  CameraDesc camera = scene.camera();
  camera.farPlane = 1e6;
  scene.setCamera(camera);
  LightDesc light = pointLight({0.0, 1.0, 5.0});
  light.falloff = true;
  light.intensity = 2.0f;
  scene.addLight(light);
  const float sigmaS = 0.3f, sigmaA = 0.1f, g = 0.5f;
  scene.setFog(volumetric(glm::vec3(sigmaS), glm::vec3(sigmaA), g));
  const double sigmaT = double(sigmaS) + double(sigmaA);
  const auto integrand = [&](double t) {
    const glm::dvec3 p(0.0, 0.0, t), toLight = glm::dvec3(0.0, 1.0, 5.0) - p;
    const double r = glm::length(toLight);
    // The angle between the light's directions of travel: from the lamp to p, then
    // from p toward the camera (-z).
    const glm::dvec3 in = -toLight / r, out(0.0, 0.0, -1.0);
    const double phase = double(engine::brdf::phaseHenyeyGreenstein(float(glm::dot(in, out)), g));
    return double(sigmaS) * std::exp(-sigmaT * t) * phase * kPi * double(light.intensity) * std::exp(-sigmaT * r) / (r * r);
  };
  const double truth = engine::test::integrate(integrand, 0.0, 200.0, 1e-8);
  rt::Integrator integrator(scene, pathSettings(1, 1, 1, 0));
  const int n = 400000;
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = integrator.traceRay(rt::Ray<double>{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 1e6}, std::uint64_t(i) + 1).x;
    sum += v;
    squares += v * v;
  }
  const double mean = sum / n, error = std::sqrt(std::max(squares / n - mean * mean, 0.0) / (n - 1));
  std::printf("single scattering: %.5f +- %.5f against the quadrature's %.5f\n", mean, error, truth);
  EXPECT_NEAR(mean, truth, 4.0 * error);
  EXPECT_LT(error, 0.05 * truth);  // the test sees a 20 % mistake
}

// A scene with a medium renders the same bytes on one thread and on two, and
// another seed gives another image.
TEST(Medium, ImagesDependOnTheSeedAloneNotTheThreads) {
  rt::RtScene scene = sceneFile("cornell.json");
  scene.setFog(volumetric(glm::vec3(0.15f), glm::vec3(0.02f), 0.3f));
  expectSeedAloneNotThreads(scene, 48, 32, 4);
}

// --describe says what each integrator draws: the medium for the path tracer, the
// exponential stand-in for the Whitted tracer.
TEST(Medium, DescribeSaysWhichFogEachTracerDraws) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}));
  scene.setFog(volumetric(glm::vec3(0.2f), glm::vec3(0.05f), 0.5f));
  rt::RenderSettings whitted = pathSettings(8, 8, 1);
  whitted.method = rt::Method::Whitted;
  EXPECT_NE(rt::describe(scene, pathSettings(8, 8, 1)).find("fog: a homogeneous medium (extinction 0.25 0.25 0.25 /m, albedo 0.8 0.8 0.8, g 0.5)"),
            std::string::npos);
  EXPECT_NE(rt::describe(scene, whitted).find(", fog (exponential)"), std::string::npos);
}

// Medium::fly's estimates per channel: a flight's weights average to the
// transmittance over a distance (not scattered) and to the scattering's density
// (scattered), by channel, over 1e6 flights: E[weight; reached] = T(d), and the
// scattered share's weights sum to sigma_s times the integral of T, (1 - T(d)) /
// sigma_t * sigma_s. Within 1 %.
TEST(Medium, FlightsAreUnbiasedPerChannel) {
  const rt::Medium medium{glm::vec3(0.2f, 0.5f, 0.0f), glm::vec3(0.3f, 1.0f, 0.4f), 0.0f};
  const double d = 2.0;
  glm::dvec3 reached(0.0), scattered(0.0);
  engine::rt::Pcg32 rng(12345u, 1u);
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    const rt::Medium::Flight f = medium.fly(d, rng.uniform(), rng.uniform());
    (f.scattered ? scattered : reached) += glm::dvec3(f.weight);
  }
  reached /= double(n);
  scattered /= double(n);
  for (int c = 0; c < 3; ++c) {
    const double sigmaT = medium.extinction[c], sigmaS = medium.scattering[c], t = std::exp(-sigmaT * d);
    EXPECT_NEAR(reached[c], t, 0.01 * t) << "channel " << c;
    const double scatteredTruth = sigmaS * (sigmaT > 0.0 ? (1.0 - t) / sigmaT : d);
    EXPECT_NEAR(scattered[c], scatteredTruth, 0.01 * std::max(scatteredTruth, 0.01)) << "channel " << c;
  }
}

}  // namespace
