// The terrain shaded once a pixel (SceneRenderer's deferred terrain: a surface
// pass, then a full-screen pass where the stencil marks terrain) against the
// terrain shaded where drawn (SceneRenderOptions::forwardTerrain): the golden
// scenes with terrain, from golden_test.cpp's views, through both backends, with
// GPU culling too (whose patches draw the surface in two halves).
//
// Why a level and not the same bytes: the deferred pass rebuilds the position from
// the stored distance along the pixel's ray, the normal's y from its x and z, and
// reads the layers at the level of detail the surface pass stored, where the
// forward draw interpolates the three and lets the sampler derive the level; each
// rounds differently in the last bits of a float. Measured: at most one level in
// 0.002-0.26 % of the channels (at 640x360). A surface not written, read at the
// wrong pixel, or shaded where the stencil does not mark terrain changes whole
// regions, by far more than a level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <tuple>

#include "app/runner.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "golden_views.h"
#include "scene_game.h"

using namespace engine;

namespace {

struct TerrainCase {
  const char* name;
  const char* file;
  double time;
  int view = 0;  // terrain.json: 1 the overview, 2 the low sun (as golden_test.cpp)
  int supersample = 0;
  bool gpuCulling = false;
};

const TerrainCase kTerrainCases[] = {
    {"demo_t0_5", "demo.json", 0.5},
    {"demo_t1_ss2", "demo.json", 1.0, 0, 2},
    {"demo_t2_culled", "demo.json", 2.0, 0, 0, true},
    {"terrain_valley", "terrain.json", 1.0},
    {"terrain_overview", "terrain.json", 1.0, 1},
    {"terrain_low_sun", "terrain.json", 1.0, 2},
    {"terrain_valley_culled", "terrain.json", 1.0, 0, 0, true}};

Image renderTerrainCase(Backend backend, const TerrainCase& c, bool forward) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + c.file);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  if (c.view == 1) test::useTerrainOverview(*scene);
  if (c.view == 2) test::useTerrainLowSun(*scene);
  SceneRenderOptions options;
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  options.supersampleOverride = c.supersample;
  options.gpuCullingOverride = c.gpuCulling;
  options.forwardTerrain = forward;
  demo::SceneGame game(std::move(scene).value(), options);
  return test::goldenFrame(backend, game, c.time);
}

using TerrainParam = std::tuple<Backend, int>;
class DeferredTerrain : public ::testing::TestWithParam<TerrainParam> {};

TEST_P(DeferredTerrain, WithinALevelOfTheTerrainShadedWhereDrawn) {
  const Backend backend = std::get<0>(GetParam());
  const TerrainCase& c = kTerrainCases[std::get<1>(GetParam())];
  const Image forward = renderTerrainCase(backend, c, true);
  const Image deferred = renderTerrainCase(backend, c, false);
  ASSERT_FALSE(forward.pixels.empty());
  ASSERT_EQ(deferred.pixels.size(), forward.pixels.size());
  const auto [largest, differing] = test::channelDifference(forward, deferred);
  std::printf("%s: %zu of %zu channels differ, by at most %d\n", c.name, differing, forward.pixels.size(), largest);
  EXPECT_LE(largest, 1) << c.name;
  EXPECT_LT(differing, forward.pixels.size() / 100) << c.name;
  if (largest > 1) {
    test::writeFailurePair(std::string("deferred_terrain_") + c.name + "_" + std::string(backendName(backend)),
                           "forward", forward, "deferred", deferred);
  }
}

ENGINE_INSTANTIATE_GOLDEN_CASES_EGL(DeferredTerrain, kTerrainCases);

}  // namespace
