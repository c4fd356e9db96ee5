// GPU culling changes no pixel (issue 16): every golden scene the scene renderer
// draws from a scene file (demo.json at two times, with MSAA, supersampling and
// hard shadows; the Cornell rooms; the terrain from three views; the material
// scene) rendered with render.gpu_culling on and off, through both backends, as
// the golden test renders them: the same bytes. tests/gl/gpu_cull_test.cpp shows
// that a non-conservative culling test does change an image.
#include <gtest/gtest.h>

#include <filesystem>
#include <tuple>

#include "app/runner.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "scene_game.h"

using namespace engine;

namespace {

struct CullingCase {
  const char* name;
  const char* file;
  double time;
  int msaa = 0;
  int supersample = 0;
  int pcf = 0;
  int view = 0;  // terrain.json: 1 the overview, 2 the low sun (as golden_test.cpp)
};

const CullingCase kCullingCases[] = {{"demo_t0_5", "demo.json", 0.5},
                                     {"demo_t2", "demo.json", 2.0},
                                     {"demo_t1_msaa4", "demo.json", 1.0, 4},
                                     {"demo_t1_ss2", "demo.json", 1.0, 0, 2},
                                     {"demo_t1_hard", "demo.json", 1.0, 0, 0, 1},
                                     {"cornell", "cornell.json", 0.0},
                                     {"cornell_pcf5", "cornell.json", 0.0, 0, 0, 5},
                                     {"terrain_valley", "terrain.json", 1.0},
                                     {"terrain_overview", "terrain.json", 1.0, 0, 0, 0, 1},
                                     {"terrain_low_sun", "terrain.json", 1.0, 0, 0, 0, 2},
                                     {"materials", "materials.json", 0.0}};

Image renderCullingCase(Backend backend, const CullingCase& c, bool culling) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + c.file);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  if (c.view == 1) {
    scene->camera.position = glm::dvec3(800.0, 650.0, 1500.0);
    scene->camera.forward = glm::normalize(glm::dvec3(0.0, -450.0, -1500.0));
  }
  if (c.view == 2) scene->lights[0].direction = glm::normalize(glm::dvec3(-0.95, 0.2, 0.2));
  SceneRenderOptions options;
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  options.msaaOverride = c.msaa;
  options.supersampleOverride = c.supersample;
  options.pcfKernelOverride = c.pcf;
  options.gpuCullingOverride = culling;
  demo::SceneGame game(std::move(scene).value(), options);
  RunOptions run;
  run.width = 640;
  run.height = 360;
  run.time = c.time;
  run.frames = 3;
  run.debugGl = true;
  Image image;
  auto status = runHeadless(backend, game, run, &image);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return image;
}

using CullingParam = std::tuple<Backend, int>;
class GpuCullingGolden : public ::testing::TestWithParam<CullingParam> {};

TEST_P(GpuCullingGolden, CulledImageIsTheUnculledOneBitForBit) {
  const Backend backend = std::get<0>(GetParam());
  const CullingCase& c = kCullingCases[std::get<1>(GetParam())];
  const Image off = renderCullingCase(backend, c, false);
  const Image on = renderCullingCase(backend, c, true);
  ASSERT_FALSE(off.pixels.empty());
  ASSERT_EQ(on.width, off.width);
  ASSERT_EQ(on.height, off.height);
  size_t differing = 0;
  for (size_t i = 0; i < off.pixels.size(); ++i) differing += on.pixels[i] != off.pixels[i];
  EXPECT_EQ(differing, 0u) << c.name << ": culling changed " << differing
                           << " bytes; both images written to build/golden-failures/";
  if (differing > 0) {
    const std::filesystem::path out = std::filesystem::path(ENGINE_BINARY_DIR) / "golden-failures";
    std::filesystem::create_directories(out);
    const std::string stem = std::string("culling_") + c.name + "_" + std::string(backendName(backend));
    (void)writePng((out / (stem + "_off.png")).string(), off);
    (void)writePng((out / (stem + "_on.png")).string(), on);
  }
}

std::string cullingCaseName(const ::testing::TestParamInfo<CullingParam>& info) {
  return std::string(backendName(std::get<0>(info.param))) + "_" + kCullingCases[std::get<1>(info.param)].name;
}

INSTANTIATE_TEST_SUITE_P(GoldenScenes, GpuCullingGolden,
                         ::testing::Combine(::testing::Values(Backend::Egl, Backend::OsMesa),
                                            ::testing::Range(0, int(std::size(kCullingCases)))),
                         cullingCaseName);

}  // namespace
