// Golden images of the tracers. Whitted: the course room, assets/scenes/cornell.json
// (hard shadows) and cornell_soft.json (the 1 x 1 area light, 4 x 4 shadow rays), at
// 320 x 240 with 4 stratified samples per pixel, seed 1. Path: cornell.json and
// materials.json (the glTF material model: textures, MASK, BLEND, emission) at 16
// samples per pixel, seed 1. Against tests/golden/{raytrace,pathtrace}_*.png.
//
// On a failure the actual image and a diff (x4 gain) are written under
// build/golden-failures/. To accept new goldens after looking at them:
//   ENGINE_UPDATE_GOLDENS=1 build/bin/raytrace_test --gtest_filter='RaytraceGolden*'
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "asset/scene_file.h"
#include "core/image.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"

namespace rt = engine::rt;
namespace fs = std::filesystem;

namespace {

// Tolerances. The render is deterministic (per-pixel RNG, one writer per pixel), so on
// the machine that made the goldens the difference is 0 whatever the thread count.
// The margin is for another compiler or libm: tan, pow and sqrt may round one ulp
// differently, which moves smooth areas by at most one 8-bit code but can flip a
// pixel whose sample lies exactly on a silhouette or shadow edge by a large step.
// A mean of 0.1 (of 255) and at most 0.2% of pixels over 8 allow ~150 flipped edge
// pixels and fail on any real change: moving the light 1 cm, a wrong gamma, a changed
// sphere or a lost reflection each move thousands of pixels.
constexpr double kMaxMean = 0.1;
constexpr double kMaxShareOver8 = 0.002;

struct GoldenCase {
  const char* name;
  const char* scene;
  rt::Method method = rt::Method::Whitted;
  int width = 320, height = 240, spp = 4;
};

class RaytraceGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(RaytraceGolden, MatchesTheGoldenImage) {
  const GoldenCase& c = GetParam();
  const std::string source = ENGINE_SOURCE_DIR;
  auto desc = engine::loadSceneFile(source + "/assets/scenes/" + c.scene);
  ASSERT_TRUE(desc) << desc.error().message;
  auto scene = rt::buildRtScene(*desc, 0.0, c.height);
  ASSERT_TRUE(scene) << scene.error().message;
  rt::RenderSettings settings;
  settings.method = c.method;
  settings.width = c.width;
  settings.height = c.height;
  settings.samplesPerPixel = c.spp;
  settings.shadowSamples = 4;
  settings.maxDepth = c.method == rt::Method::Path ? 16 : 5;
  settings.seed = 1;
  const rt::RenderResult result = rt::Integrator(*scene, settings).render();
  const engine::Image actual = rt::toImage(result.image, scene->render());

  const std::string goldenPath = source + "/tests/golden/" + c.name + ".png";
  if (const char* update = std::getenv("ENGINE_UPDATE_GOLDENS"); update && std::string(update) == "1") {
    ASSERT_TRUE(engine::writePng(goldenPath, actual).ok());
    GTEST_SKIP() << "wrote " << goldenPath << "; look at it before committing";
  }
  auto golden = engine::readPng(goldenPath);
  ASSERT_TRUE(golden) << golden.error().message;
  auto diff = engine::compareImages(actual, *golden, 8);
  ASSERT_TRUE(diff) << diff.error().message;
  const bool pass = diff->meanAbs <= kMaxMean && diff->shareOver <= kMaxShareOver8;
  if (!pass) {
    const fs::path dir = fs::path(ENGINE_BINARY_DIR) / "golden-failures";
    fs::create_directories(dir);
    (void)engine::writePng((dir / (std::string(c.name) + "_actual.png")).string(), actual);
    (void)engine::writePng((dir / (std::string(c.name) + "_diff.png")).string(), engine::diffImage(actual, *golden));
  }
  EXPECT_TRUE(pass) << c.name << ": mean " << diff->meanAbs << ", max " << diff->maxAbs << ", share over 8 "
                    << diff->shareOver << "; actual and diff in " << ENGINE_BINARY_DIR << "/golden-failures/";
}

INSTANTIATE_TEST_SUITE_P(Cornell, RaytraceGolden,
                         ::testing::Values(GoldenCase{"raytrace_cornell", "cornell.json"},
                                           GoldenCase{"raytrace_cornell_soft", "cornell_soft.json"},
                                           GoldenCase{"pathtrace_cornell", "cornell.json", rt::Method::Path, 320, 240, 16},
                                           GoldenCase{"pathtrace_materials", "materials.json", rt::Method::Path, 320, 180, 16}),
                         [](const auto& param) { return std::string(param.param.name); });

// The course room's lit floor in front of the blue sphere, against the course's formula
// computed here: 0.75 * (0.1 + 0.9 N.L), N = +y, no shadow, at the pixel centre.
TEST(RaytraceCornell, FloorPixelIsTheCourseFormula) {
  auto desc = engine::loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  ASSERT_TRUE(desc) << desc.error().message;
  auto scene = rt::analyticRtScene(*desc);
  ASSERT_TRUE(scene);
  rt::RenderSettings settings;
  settings.width = 320;
  settings.height = 240;
  const int x = 40, y = 230;  // bottom left: the floor, well clear of the spheres' shadows
  const double yScale = std::tan(M_PI / 6), xScale = yScale * 320.0 / 240.0;
  const glm::dvec3 d = glm::normalize(glm::dvec3((2 * (x + 0.5) / 320 - 1) * xScale, -(2 * (y + 0.5) / 240 - 1) * yScale, 1));
  const glm::dvec3 eye(0, 1.5, -3);
  const glm::dvec3 p = eye + d * (-eye.y / d.y);
  const double nDotL = glm::normalize(glm::dvec3(0, 2.8, 2) - p).y;
  const glm::vec3 c = rt::Integrator(*scene, settings).renderPixel(x, y);
  EXPECT_NEAR(c.r, 0.75 * (0.1 + 0.9 * nDotL), 1e-5);
}

}  // namespace
