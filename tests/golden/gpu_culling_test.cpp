// GPU culling changes no pixel (issue 16): every golden scene of golden_test.cpp
// (demo.json at two times, with MSAA, supersampling and hard shadows; the Cornell
// rooms; the terrain from three views; the material scene; the viewer's robot with
// LBS and DQS and its Khronos samples, instancing included) rendered with
// render.gpu_culling on and off, through both backends, as the golden test
// renders them: the same bytes. tests/render/gpu_cull_test.cpp shows
// that a non-conservative culling test does change an image.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <tuple>

#include "app/runner.h"
#include "asset/gltf_loader.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "golden_views.h"
#include "scene_game.h"
#include "viewer_scene.h"

using namespace engine;

namespace {

struct CullingCase {
  const char* name;
  const char* file;  // a scene under assets/scenes, or a model for the viewer (below)
  double time;
  int msaa = 0;
  int supersample = 0;
  int pcf = 0;
  int view = 0;  // terrain.json: 1 the overview, 2 the low sun (as golden_test.cpp)
  // The viewer's goldens: the robot (clip, dual quaternions), or a Khronos sample
  // under ../shared/gltf-samples (skipped without it) in its rest pose.
  int clip = -2;  // -2: a scene file
  bool dqs = false;
  bool sample = false;
};

const CullingCase kCullingCases[] = {
    {"demo_t0_5", "demo.json", 0.5},
    {"demo_t2", "demo.json", 2.0},
    {"demo_t1_msaa4", "demo.json", 1.0, 4},
    {"demo_t1_ss2", "demo.json", 1.0, 0, 2},
    {"demo_t1_hard", "demo.json", 1.0, 0, 0, 1},
    {"cornell", "cornell.json", 0.0},
    {"cornell_pcf5", "cornell.json", 0.0, 0, 0, 5},
    {"terrain_valley", "terrain.json", 1.0},
    {"terrain_overview", "terrain.json", 1.0, 0, 0, 0, 1},
    {"terrain_low_sun", "terrain.json", 1.0, 0, 0, 0, 2},
    {"materials", "materials.json", 0.0},
    {"robot_walk_t0_3", "character.gltf", 0.3, 0, 0, 0, 0, 1},
    {"robot_wave_dqs_t0_6", "character.gltf", 0.6, 0, 0, 0, 0, 2, true},
    {"sample_multiuv", "MultiUVTest/glTF-Binary/MultiUVTest.glb", 0.0, 0, 0, 0, 0, -1, false, true},
    {"sample_texture_transform", "TextureTransformTest/glTF/TextureTransformTest.gltf", 0.0, 0, 0, 0, 0, -1, false, true},
    {"sample_texture_settings", "TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb", 0.0, 0, 0, 0, 0, -1, false, true},
    {"sample_instancing", "SimpleInstancing/glTF-Binary/SimpleInstancing.glb", 0.0, 0, 0, 0, 0, -1, false, true},
    {"sample_lights_lamp", "LightsPunctualLamp/glTF/LightsPunctualLamp.gltf", 0.0, 0, 0, 0, 0, -1, false, true}};

const std::string kCullingSamples = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/";

// The game golden_test.cpp's case draws, with culling on or off.
std::unique_ptr<Game> makeCullingGame(const CullingCase& c, bool culling) {
  if (c.clip != -2) {
    auto model = loadGltf(c.sample ? kCullingSamples + c.file
                                   : std::string(ENGINE_SOURCE_DIR) + "/assets/models/" + c.file);
    EXPECT_TRUE(model.ok()) << model.error().message;
    if (!model) return nullptr;
    viewer::ViewerSettings settings;
    settings.clip = c.clip;
    settings.skinMode = c.dqs ? SkinMode::DualQuat : SkinMode::Linear;
    if (c.sample && std::string(c.file).rfind("Texture", 0) == 0) settings.viewDirection = glm::dvec3(0.0, 0.0, 1.0);
    settings.gpuCulling = culling;
    return std::make_unique<viewer::ViewerScene>(std::string(ENGINE_SOURCE_DIR) + "/shaders", std::move(model).value(),
                                                 settings);
  }
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + c.file);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return nullptr;
  if (c.view == 1) test::useTerrainOverview(*scene);
  if (c.view == 2) test::useTerrainLowSun(*scene);
  SceneRenderOptions options;
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  options.msaaOverride = c.msaa;
  options.supersampleOverride = c.supersample;
  options.pcfKernelOverride = c.pcf;
  options.gpuCullingOverride = culling;
  return std::make_unique<demo::SceneGame>(std::move(scene).value(), options);
}

Image renderCullingCase(Backend backend, const CullingCase& c, bool culling) {
  auto game = makeCullingGame(c, culling);
  if (!game) return {};
  return test::goldenFrame(backend, *game, c.time);
}

using CullingParam = std::tuple<Backend, int>;
class GpuCullingGolden : public ::testing::TestWithParam<CullingParam> {};

TEST_P(GpuCullingGolden, CulledImageIsTheUnculledOneBitForBit) {
  const Backend backend = std::get<0>(GetParam());
  const CullingCase& c = kCullingCases[std::get<1>(GetParam())];
  if (c.sample && !std::filesystem::exists(kCullingSamples + c.file))
    GTEST_SKIP() << kCullingSamples + c.file << " not found (../shared/gltf-samples absent)";
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
    test::writeFailurePair(std::string("culling_") + c.name + "_" + std::string(backendName(backend)), "off", off,
                           "on", on);
  }
}

ENGINE_INSTANTIATE_GOLDEN_CASES_EGL(GpuCullingGolden, kCullingCases);

}  // namespace
