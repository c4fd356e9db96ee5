// The path tracer against answers known in closed form (pbrt-v4's integrators_test
// habit): the white furnace, a convex diffuse object under a uniform sky, irradiance
// from a cone sun and from an area light that fills the sky; its convergence as
// 1 / sqrt(spp); and images that depend on the seed alone, not the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "asset/scene_file.h"
#include "raytrace/integrator.h"
#include "raytrace/scene_builder.h"
#include "test_scenes.h"

namespace {

// pbrt's white furnace: inside a closed diffuse sphere of albedo 0.5 that emits 0.5,
// radiance is 0.5 + 0.5 (0.5 + 0.5 (...)) = 1 everywhere. Every bounce, Russian
// roulette and the emission of surfaces reached by BSDF samples must be right.
TEST(PathTracer, WhiteFurnaceIsOne) {
  for (const rt::Precision precision : {rt::Precision::Float, rt::Precision::Double}) {
    rt::RtScene scene = emptyScene(lookAt({0.1, -0.2, 0.3}, {1, 0.5, 2}, 90.0));
    MaterialDesc wall = classic(glm::vec3(0.5f), 0.0f, 1.0f);
    wall.emission = glm::vec3(0.5f);
    scene.addSphere({0, 0, 0}, 2.0, scene.addMaterial(wall));
    rt::RenderSettings settings = pathSettings(16, 16, 256);
    settings.precision = precision;
    const rt::RenderResult r = rt::Integrator(scene, settings).render();
    const glm::dvec3 mean = meanOf(r.image);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.025);
    // Each pixel on its own (256 samples) is within 10 %: no pixel lost its paths.
    for (const glm::vec3& p : r.image.pixels) ASSERT_NEAR(p.x, 1.0, 0.1);
  }
}

// A glass ball (KHR_materials_transmission and _volume: white, ior 1.5) under a sky of
// radiance 1, seen head-on through its centre. Without absorption every path leaves
// it again, reflected or refracted: it shows the sky's 1, solid or thin-walled. With
// the volume absorbing half of the light over its diameter (attenuationColor 0.5 at
// attenuationDistance 2), what comes straight through is (1 - F)^2 0.5, F = 0.04,
// and the light reflected inside adds a geometric series: F + (1 - F)^2 0.5 /
// (1 - 0.5 F) = 0.5102 (rays 2.5 degrees off the axis: paths 0.2 % shorter).
TEST(PathTracer, GlassBallUnderAUniformSkyTransmitsWhatItDoesNotAbsorb) {
  struct Case {
    float thickness, attenuationColor, expected;
  };
  for (const Case& c : {Case{0.0f, 1.0f, 1.0f}, Case{2.0f, 1.0f, 1.0f}, Case{2.0f, 0.5f, 0.5102f}}) {
    rt::RtScene scene = emptyScene(lookAt({0, 0, -3}, {0, 0, 0}, 10.0));
    engine::SkyDesc sky;
    sky.enabled = false;
    sky.background = glm::vec3(1.0f);
    scene.setSky(sky);
    engine::RenderDesc render = scene.render();
    render.shading = engine::Shading::Pbr;
    scene.setRender(render);
    MaterialDesc glass;
    glass.color = glm::vec3(1.0f);
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.layers.transmission = 1.0f;
    glass.layers.thickness = c.thickness;
    glass.layers.attenuationColor = glm::vec3(c.attenuationColor);
    glass.layers.attenuationDistance = 2.0f;
    scene.addSphere({0, 0, 0}, 1.0, scene.addMaterial(glass));
    const rt::RenderResult r = rt::Integrator(scene, pathSettings(8, 8, 256)).render();
    const glm::dvec3 mean = meanOf(r.image);
    std::printf("glass ball, thickness %g, attenuation %g: %.4f (expected %.4f)\n", c.thickness, c.attenuationColor,
                mean.x, c.expected);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mean[k], c.expected, 0.015) << "thickness " << c.thickness << ", attenuation " << c.attenuationColor;
  }
}

// The max-depth knob stops paths where it says, in the furnace where each bounce is
// worth half the one before.
TEST(PathTracer, MaxDepthCountsBounces) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 90.0));
  MaterialDesc wall = classic(glm::vec3(0.5f), 0.0f, 1.0f);
  wall.emission = glm::vec3(0.5f);
  scene.addSphere({0, 0, 0}, 2.0, scene.addMaterial(wall));
  for (const int depth : {0, 1, 2, 5}) {
    rt::RenderSettings settings = pathSettings(8, 8, 64, depth);
    settings.rouletteDepth = 100;  // exact sums, no roulette noise
    const glm::dvec3 mean = meanOf(rt::Integrator(scene, settings).render().image);
    // Depth 0 is direct light: the wall's own 0.5 and half of what the walls it sees
    // emit; every bounce adds half of the one before: 1 - 0.5^(depth + 2).
    const double expected = 1.0 - std::pow(0.5, depth + 2);
    EXPECT_NEAR(mean.x, expected, 1e-4) << "depth " << depth;
  }
}

// A convex Lambert sphere under a uniform sky of radiance 1 reflects its albedo in
// every direction: the environment's importance sampling and the BSDF samples that
// escape, weighed by MIS, add up to exactly that.
TEST(PathTracer, ConvexDiffuseUnderUniformSkyShowsItsAlbedo) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, -3}, {0, 0, 0}, 60.0));
  engine::SkyDesc sky;
  sky.enabled = false;
  sky.background = glm::vec3(1.0f);
  scene.setSky(sky);
  scene.addSphere({0, 0, 0}, 1.0, scene.addMaterial(classic(glm::vec3(0.6f, 0.3f, 0.9f), 0.0f, 1.0f)));
  const rt::Integrator integrator(scene, pathSettings(24, 24, 256));
  const rt::RenderResult r = integrator.render();
  const rt::Framebuffer& image = r.image;
  // The centre 8 x 8 pixels all see the sphere.
  glm::dvec3 sum(0.0);
  for (int y = 8; y < 16; ++y) {
    for (int x = 8; x < 16; ++x) sum += glm::dvec3(image.at(x, y));
  }
  const glm::dvec3 mean = sum / 64.0;
  EXPECT_NEAR(mean.x, 0.6, 0.01);
  EXPECT_NEAR(mean.y, 0.3, 0.01);
  EXPECT_NEAR(mean.z, 0.9, 0.01);
  EXPECT_NEAR(image.at(0, 0).x, 1.0, 1e-6);  // the sky itself
}

// A white floor seen from above, lit only by `light`: the mean radiance of the
// centre of the image.
double floorRadiance(const LightDesc& light, int spp = 64) {
  rt::RtScene scene = emptyScene(lookAt({0, 5, 0}, {0, 0, 0.001}, 10.0));
  scene.addPlane({0, 0, 0}, {0, 1, 0}, scene.addMaterial(classic(glm::vec3(1.0f), 0.0f, 1.0f)));
  scene.addLight(light);
  const rt::RenderResult r = rt::Integrator(scene, pathSettings(8, 8, spp, 0)).render();
  return meanOf(r.image).x;
}

// A sun of any angular size gives a surface facing it the irradiance pi I of the
// delta sun, so a white Lambert floor shows I either way (the engine's convention).
TEST(PathTracer, ConeSunGivesTheIrradianceOfTheDeltaSun) {
  LightDesc sun;
  sun.type = LightType::Sun;
  sun.direction = {0, 1, 0};
  sun.intensity = 0.7f;
  EXPECT_NEAR(floorRadiance(sun), 0.7, 1e-5);
  for (const float angle : {0.53f, 5.0f, 20.0f}) {
    sun.angleDegrees = angle;
    EXPECT_NEAR(floorRadiance(sun), 0.7, 0.7 * 0.01) << angle;
  }
}

// An area light emits radiance I: a rectangle that fills nearly all of the floor's
// sky makes a white floor nearly I, and one far away acts as a point light of
// power I * area / pi (the inverse-square law).
TEST(PathTracer, AreaLightEmitsItsIntensityAsRadiance) {
  LightDesc area;
  area.type = LightType::Area;
  area.position = {0, 0.01, 0};
  area.edgeU = {2000, 0, 0};
  area.edgeV = {0, 0, 2000};  // u x v points down, toward the floor
  area.intensity = 0.8f;
  area.shadows = false;  // the camera sees the floor through it: lights are not geometry
  EXPECT_NEAR(floorRadiance(area), 0.8, 0.8 * 0.01);
  area.position = {0, 50, 0};
  area.edgeU = {1, 0, 0};
  area.edgeV = {0, 0, 1};
  // E = I A cos cos / d^2 = 0.8 / 2500; a Lambert floor reflects E / pi.
  EXPECT_NEAR(floorRadiance(area, 256), 0.8 / 2500.0 / M_PI, 0.8 / 2500.0 / M_PI * 0.02);
}

engine::SceneDesc courseRoom() {
  auto scene = engine::loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  EXPECT_TRUE(scene) << (scene ? "" : scene.error().message);
  return *scene;
}

double rmse(const rt::Framebuffer& a, const rt::Framebuffer& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(a.pixels[i]) - glm::dvec3(b.pixels[i]);
    sum += glm::dot(d, d) / 3.0;
  }
  return std::sqrt(sum / double(a.pixels.size()));
}

// Monte Carlo's promise: the error against a 4096-spp image of the course room falls
// as 1 / sqrt(spp), within 20 %, over four doublings (16 to 256 spp). A biased
// estimator flattens out; correlated samples fall more slowly.
TEST(PathTracer, ErrorFallsAsOneOverSqrtSpp) {
  auto rtScene = rt::buildRtScene(courseRoom(), 0.0);
  ASSERT_TRUE(rtScene) << rtScene.error().message;
  rt::RenderSettings settings = pathSettings(32, 18, 4096, 16);
  settings.seed = 99;
  const rt::Framebuffer reference = rt::Integrator(*rtScene, settings).render().image;
  std::vector<double> scaled;
  for (int spp = 16; spp <= 256; spp *= 2) {
    settings.samplesPerPixel = spp;
    settings.seed = std::uint64_t(spp);
    const double error = rmse(rt::Integrator(*rtScene, settings).render().image, reference);
    // The reference's own noise adds to the difference: remove its share (its
    // variance is spp / 4096 of this image's).
    const double corrected = error / std::sqrt(1.0 + double(spp) / 4096.0);
    scaled.push_back(corrected * std::sqrt(double(spp)));
  }
  for (std::size_t i = 1; i < scaled.size(); ++i) {
    EXPECT_NEAR(scaled[i] / scaled[0], 1.0, 0.2) << "rmse * sqrt(spp) at " << (16 << i) << " spp vs 16";
  }
}

// The image is a function of the seed and spp: one thread or two, the same bytes;
// another seed, another image.
TEST(PathTracer, DeterministicWhateverTheThreadCount) {
  auto rtScene = rt::buildRtScene(courseRoom(), 0.0);
  ASSERT_TRUE(rtScene);
  rt::RenderSettings settings = pathSettings(40, 24, 8, 16);
  settings.threads = 1;
  const rt::Framebuffer one = rt::Integrator(*rtScene, settings).render().image;
  settings.threads = 2;
  settings.tileSize = 7;
  const rt::Framebuffer two = rt::Integrator(*rtScene, settings).render().image;
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  EXPECT_EQ(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(glm::vec3)), 0);
  settings.seed = 2;
  const rt::Framebuffer other = rt::Integrator(*rtScene, settings).render().image;
  EXPECT_NE(std::memcmp(one.pixels.data(), other.pixels.data(), one.pixels.size() * sizeof(glm::vec3)), 0);
}

}  // namespace

namespace {

// Passes compose: samples [0, 4) and [4, 8) averaged are samples [0, 8), up to the
// rounding of the two means (the window's progressive image is the offline one).
TEST(PathTracer, PassesOfSamplesComposeToTheWholeRender) {
  auto rtScene = rt::buildRtScene(courseRoom(), 0.0);
  ASSERT_TRUE(rtScene);
  rt::RenderSettings settings = pathSettings(24, 16, 8, 16);
  const rt::Framebuffer whole = rt::Integrator(*rtScene, settings).render().image;
  settings.samplesPerPixel = 4;
  const rt::Framebuffer first = rt::Integrator(*rtScene, settings).render().image;
  settings.firstSample = 4;
  const rt::Framebuffer second = rt::Integrator(*rtScene, settings).render().image;
  double worst = 0.0, differs = 0.0;
  for (std::size_t i = 0; i < whole.pixels.size(); ++i) {
    const glm::vec3 mean = 0.5f * (first.pixels[i] + second.pixels[i]);
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, double(std::abs(mean[c] - whole.pixels[i][c])) / std::max(1e-3, double(whole.pixels[i][c])));
      differs = std::max(differs, double(std::abs(first.pixels[i][c] - second.pixels[i][c])));
    }
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(differs, 0.01);  // the two passes are different samples
}

}  // namespace
