// The environment (raytrace/environment.h): the lat-long convention both ways, an
// image's radiance, where its halves land with and without rotation, and the
// gradient sky exactly as the Whitted integrator's escaped() drew it before.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../support/radiance_file.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "core/linear_image.h"
#include "raytrace/environment.h"
#include "raytrace/rt_scene.h"
#include "scene/scene_images.h"

namespace rt = engine::rt;
using engine::SkyDesc;
using engine::test::ScratchFolder;
using rt::Environment;

namespace {

// Uniform on the sphere, plus the cases a lat-long map gets wrong: the poles and the
// u seam (-z), approached from both sides.
std::vector<glm::vec3> testDirections(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<glm::vec3> dirs;
  while (int(dirs.size()) < count) {
    const glm::vec3 d(uniform(rng), uniform(rng), uniform(rng));
    const float len = glm::length(d);
    if (len > 1e-3f && len <= 1.0f) dirs.push_back(d / len);
  }
  for (float e : {1e-1f, 1e-2f, 1e-3f, 1e-4f, 1e-5f, 1e-6f}) {
    for (float s : {-1.0f, 1.0f}) {
      dirs.push_back(glm::normalize(glm::vec3(e, s, 0.3f * e)));           // near a pole
      dirs.push_back(glm::normalize(glm::vec3(s * e, uniform(rng), -1.0f)));  // beside the seam
    }
  }
  dirs.insert(dirs.end(), {{0, 0, -1}, {-0.0f, 0, -1}, {0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}});
  return dirs;
}

float angleBetween(const glm::vec3& a, const glm::vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The gradient sky of whitted_tracer.cpp's escaped() before the environment existed,
// copied verbatim: the new code must give these very bits.
glm::vec3 oldEscaped(const SkyDesc& sky, std::optional<glm::vec3> sunDirection, const glm::vec3& dir) {
  if (!sky.enabled) return sky.background;
  const glm::vec3 d = glm::normalize(glm::vec3(dir));
  glm::vec3 color = d.y >= 0.0f ? glm::mix(sky.horizon, sky.zenith, std::sqrt(d.y))
                                : glm::mix(sky.horizon, sky.ground, std::sqrt(-d.y));
  if (sky.sunDisk && sunDirection) {
    const float c = glm::dot(d, *sunDirection);
    const float s = std::clamp((c - 0.9995f) / (0.9998f - 0.9995f), 0.0f, 1.0f);
    color += glm::vec3(4.0f, 3.6f, 3.0f) * (s * s * (3.0f - 2.0f * s));
  }
  return color;
}

Environment imageSky(const std::filesystem::path& path, float intensity = 1.0f, float rotation = 0.0f) {
  SkyDesc sky;
  sky.image = path.string();
  sky.intensity = intensity;
  sky.rotationDegrees = rotation;
  auto image = engine::readLinearImage(sky.image);
  EXPECT_TRUE(image.ok()) << image.error().message;
  if (!image) return Environment();
  auto env = Environment::create(sky, std::nullopt, std::make_shared<const engine::FloatImage>(std::move(image).value()));
  EXPECT_TRUE(env.ok()) << env.error().message;
  return env.ok() ? std::move(env).value() : Environment();
}

const glm::vec3 kRed(0.75f, 0.0f, 0.0f), kGreen(0.0f, 0.5f, 0.0f), kBlue(0.0f, 0.0f, 0.25f);

}  // namespace

TEST(Environment, LatLongPinsTheAxes) {
  EXPECT_EQ(Environment::uvOf({0, 0, 1}), glm::vec2(0.5f, 0.5f));
  EXPECT_EQ(Environment::uvOf({-1, 0, 0}), glm::vec2(0.75f, 0.5f));
  EXPECT_EQ(Environment::uvOf({1, 0, 0}), glm::vec2(0.25f, 0.5f));
  // Both zeros of x on the seam land on its u = 0 side, never on u = 1.
  EXPECT_EQ(Environment::uvOf({0, 0, -1}), glm::vec2(0.0f, 0.5f));
  EXPECT_EQ(Environment::uvOf({-0.0f, 0, -1}), glm::vec2(0.0f, 0.5f));
  EXPECT_EQ(Environment::uvOf({0, 1, 0}), glm::vec2(0.5f, 0.0f));
  EXPECT_EQ(Environment::uvOf({0, -1, 0}), glm::vec2(0.5f, 1.0f));
  EXPECT_EQ(Environment::uvOf({0, 0, 2}), glm::vec2(0.5f, 0.5f));  // any length
  const float tolerance = 1e-6f;
  EXPECT_LT(glm::length(Environment::directionOf({0.5f, 0.5f}) - glm::vec3(0, 0, 1)), tolerance);
  EXPECT_LT(glm::length(Environment::directionOf({0.75f, 0.5f}) - glm::vec3(-1, 0, 0)), tolerance);
  EXPECT_LT(glm::length(Environment::directionOf({0.25f, 0.5f}) - glm::vec3(1, 0, 0)), tolerance);
  EXPECT_LT(glm::length(Environment::directionOf({0.5f, 0.0f}) - glm::vec3(0, 1, 0)), tolerance);
  EXPECT_LT(glm::length(Environment::directionOf({0.1f, 1.0f}) - glm::vec3(0, -1, 0)), tolerance);
}

// direction -> uv -> direction over 1e5 directions, the poles and the seam included;
// and uv -> direction -> uv, where u is compared around the circle and weighted by
// the parallel's radius (u means less and less toward a pole).
TEST(Environment, LatLongDirectionAndUvAreInverse) {
  float worstAngle = 0.0f, worstUv = 0.0f;
  for (const glm::vec3& d : testDirections(100000)) {
    const glm::vec2 uv = Environment::uvOf(d);
    ASSERT_TRUE(uv.x >= 0.0f && uv.x < 1.0f && uv.y >= 0.0f && uv.y <= 1.0f) << uv.x << " " << uv.y;
    worstAngle = std::max(worstAngle, angleBetween(Environment::directionOf(uv), d));
    const glm::vec2 back = Environment::uvOf(Environment::directionOf(uv));
    const float du = std::abs(back.x - uv.x);
    const float sinTheta = std::sin(uv.y * 3.14159265f);
    worstUv = std::max({worstUv, std::min(du, 1.0f - du) * sinTheta, std::abs(back.y - uv.y)});
  }
  std::printf("lat-long round trip: worst %.3g rad, worst uv %.3g\n", worstAngle, worstUv);
  // Float's rounding of atan2, sin and cos: a few ulps of an angle near pi.
  EXPECT_LT(worstAngle, 2e-6f);
  EXPECT_LT(worstUv, 2e-6f);
}

TEST(Environment, ConstantImageGivesItsColourTimesIntensityEverywhere) {
  ScratchFolder folder;
  const glm::vec3 color(0.75f, 0.5f, 0.25f);
  // 16 wide: stb's run-length layout; 3 wide: flat pixels.
  for (const glm::ivec2 size : {glm::ivec2(16, 8), glm::ivec2(3, 2)}) {
    const auto path = folder / "constant.hdr";
    engine::test::writeHdr(path, size.x, size.y, std::vector<glm::vec3>(std::size_t(size.x * size.y), color));
    for (const float rotation : {0.0f, 33.0f}) {
      const Environment env = imageSky(path, 2.5f, rotation);
      ASSERT_TRUE(env.hasImage());
      EXPECT_FALSE(env.isConstant());
      EXPECT_EQ(env.resolution(), size);
      for (const glm::vec3& d : testDirections(2000)) {
        const glm::vec3 l = env.radiance(d);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(l[c], color[c] * 2.5f, 1e-6f) << d.x << " " << d.y << " " << d.z;
      }
    }
  }
}

// Two texels across: red at u = 0.25 (+x), green at u = 0.75 (-x), half and half on
// the seam (-z) and at +z. Turning the image by 90 degrees (counter-clockwise seen
// from above) takes +x to -z and -x to +z; by -90 the other way.
TEST(Environment, TwoTexelImagePinsTheConventionAndTheRotation) {
  ScratchFolder folder;
  engine::test::writeHdr(folder / "halves.hdr", 2, 1, {kRed, kGreen});
  const glm::vec3 half = (kRed + kGreen) * 0.5f;
  const float e = 1e-6f;
  auto expectAt = [&](const Environment& env, glm::vec3 dir, glm::vec3 want, const char* what) {
    const glm::vec3 got = env.radiance(glm::normalize(dir));
    EXPECT_LT(glm::length(got - want), e) << what << ": got " << got.r << " " << got.g << " " << got.b;
  };
  const Environment still = imageSky(folder / "halves.hdr");
  expectAt(still, {1, 0, 0}, kRed, "+x");
  expectAt(still, {-1, 0, 0}, kGreen, "-x");
  expectAt(still, {0, 0, 1}, half, "+z");
  expectAt(still, {0, 0, -1}, half, "-z");
  expectAt(still, {1, 0.9f, 0}, kRed, "+x, up: v is clamped");
  expectAt(still, {1, 0, -1}, (kRed * 0.75f + kGreen * 0.25f), "+x-z: a quarter turn toward the seam");
  const Environment turned = imageSky(folder / "halves.hdr", 1.0f, 90.0f);
  expectAt(turned, {0, 0, -1}, kRed, "turned 90, -z");
  expectAt(turned, {0, 0, 1}, kGreen, "turned 90, +z");
  expectAt(turned, {1, 0, 0}, half, "turned 90, +x");
  const Environment back = imageSky(folder / "halves.hdr", 1.0f, -90.0f);
  expectAt(back, {0, 0, 1}, kRed, "turned -90, +z");
  expectAt(back, {0, 0, -1}, kGreen, "turned -90, -z");
}

// One texel across and two down: the top row at the zenith, the bottom at the nadir.
TEST(Environment, TopRowIsTheZenith) {
  ScratchFolder folder;
  engine::test::writeHdr(folder / "rows.hdr", 1, 2, {kBlue, kRed});
  const Environment env = imageSky(folder / "rows.hdr");
  EXPECT_LT(glm::length(env.radiance({0, 1, 0}) - kBlue), 1e-6f);
  EXPECT_LT(glm::length(env.radiance({0, -1, 0}) - kRed), 1e-6f);
  EXPECT_LT(glm::length(env.radiance({0.3f, 0, 1}) - (kBlue + kRed) * 0.5f), 1e-6f);  // the horizon
}

// A PNG sky is sRGB: decoded to linear before it is filtered and scaled.
TEST(Environment, PngImageIsLinearised) {
  ScratchFolder folder;
  engine::Image png(4, 2);
  for (std::size_t i = 0; i < png.pixels.size(); ++i) png.pixels[i] = 128;
  ASSERT_TRUE(engine::writePng((folder / "grey.png").string(), png).ok());
  const Environment env = imageSky(folder / "grey.png", 2.0f);
  EXPECT_NEAR(env.radiance({0.2f, 0.5f, -0.7f}).g, 2.0f * 0.2158605f, 1e-6f);
}

TEST(Environment, GradientSkyIsTheOldEscaped) {
  SkyDesc sky;
  sky.zenith = {0.1f, 0.3f, 0.9f};
  sky.horizon = {0.7f, 0.75f, 0.8f};
  sky.ground = {0.2f, 0.18f, 0.1f};
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
  // Directions inside and around the sun's disk too (cosine above 0.9995), where its
  // smoothstep is neither 0 nor 1.
  std::vector<glm::vec3> dirs = testDirections(20000);
  std::mt19937 rng(3);
  std::normal_distribution<float> jitter(0.0f, 0.02f);
  int inDisk = 0;
  for (int i = 0; i < 2000; ++i) {
    dirs.push_back(glm::normalize(sun + glm::vec3(jitter(rng), jitter(rng), jitter(rng))));
    inDisk += glm::dot(dirs.back(), sun) > 0.9995f;
  }
  ASSERT_GT(inDisk, 20);
  for (const bool sunDisk : {true, false}) {
    sky.sunDisk = sunDisk;
    for (const std::optional<glm::vec3> sunDirection : {std::optional<glm::vec3>(sun), std::optional<glm::vec3>()}) {
      auto env = Environment::create(sky, sunDirection);
      ASSERT_TRUE(env.ok());
      EXPECT_FALSE(env->hasImage() || env->isConstant());
      EXPECT_EQ(env->resolution(), glm::ivec2(512, 256));
      for (const glm::vec3& d : dirs) {
        ASSERT_EQ(env->radiance(d), oldEscaped(sky, sunDirection, d)) << d.x << " " << d.y << " " << d.z;
        // Lengths other than 1 too, as escaped() got unnormalised ray directions.
        ASSERT_EQ(env->radiance(d * 3.0f), oldEscaped(sky, sunDirection, d * 3.0f));
      }
    }
  }
  // radiance(d, false): the gradient without the disk, for a sampler that has the sun.
  sky.sunDisk = true;
  auto env = Environment::create(sky, sun);
  ASSERT_TRUE(env.ok());
  SkyDesc noDisk = sky;
  noDisk.sunDisk = false;
  EXPECT_GT(env->radiance(sun).r, 4.0f);
  EXPECT_EQ(env->radiance(sun, false), oldEscaped(noDisk, sun, sun));
}

TEST(Environment, DisabledSkyIsTheBackgroundEverywhere) {
  EXPECT_TRUE(Environment().isConstant());
  EXPECT_EQ(Environment().radiance({0, 1, 0}), glm::vec3(0.0f));
  SkyDesc sky;
  sky.enabled = false;
  sky.background = {0.2f, 0.1f, 0.05f};
  auto env = Environment::create(sky, glm::vec3(0, 1, 0));
  ASSERT_TRUE(env.ok());
  EXPECT_TRUE(env->isConstant());
  EXPECT_FALSE(env->hasImage());
  EXPECT_EQ(env->resolution(), glm::ivec2(512, 256));
  for (const glm::vec3& d : testDirections(100)) EXPECT_EQ(env->radiance(d), sky.background);
}

// The scene layer decodes the image (scene/scene_images.h); an image sky handed
// over without it is an error naming the file, not a black sky.
TEST(Environment, MissingImageIsAnErrorNamingIt) {
  SkyDesc sky;
  sky.image = "/nonexistent/sky.hdr";
  auto env = Environment::create(sky, std::nullopt);
  ASSERT_FALSE(env.ok());
  EXPECT_EQ(env.error().message, "/nonexistent/sky.hdr: the sky's image was not decoded (scene/scene_images.h)");
}

// The scene's environment: the image from the scene file, or the gradient with the
// last sun's disk, kept up to date by setSky and addLight as escaped() saw them.
TEST(Environment, RtSceneBuildsItFromTheSky) {
  ScratchFolder folder;
  engine::test::writeHdr(folder / "halves.hdr", 2, 1, {kRed, kGreen});
  const std::string path = (folder / "s.json").string();
  auto desc = engine::parseScene(R"({"sky": {"image": "halves.hdr", "intensity": 2}})", path);
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto images = engine::SceneImages::load(*desc);
  ASSERT_TRUE(images.ok()) << images.error().message;
  auto scene = rt::RtScene::fromSceneDesc(*desc, *images);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(scene->environment().hasImage());
  EXPECT_LT(glm::length(scene->environment().radiance({1, 0, 0}) - kRed * 2.0f), 1e-6f);

  // The file went away after the scene file was read: the scene layer's error names
  // the scene, the key and the image.
  std::filesystem::remove(folder / "halves.hdr");
  auto gone = engine::SceneImages::load(*desc);
  ASSERT_FALSE(gone.ok());
  EXPECT_EQ(gone.error().message, path + ": /sky/image: " + (folder / "halves.hdr").string() + ": no such file");

  rt::RtScene plain;
  SkyDesc sky;
  plain.setSky(sky);
  const glm::vec3 up(0, 1, 0);
  EXPECT_EQ(plain.environment().radiance(up), oldEscaped(sky, std::nullopt, up));
  engine::LightDesc sunLight;
  sunLight.type = engine::LightType::Sun;
  sunLight.direction = {0, 1, 0};
  plain.addLight(sunLight);
  EXPECT_EQ(plain.environment().radiance(up), oldEscaped(sky, up, up));
  EXPECT_GT(plain.environment().radiance(up).r, 4.0f);
  plain.setEnvironment(Environment());
  plain.addLight(sunLight);
  EXPECT_EQ(plain.environment().radiance(up), glm::vec3(0.0f));  // set environments stay
}
