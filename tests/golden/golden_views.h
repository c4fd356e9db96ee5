#pragma once
// What the golden tests share: terrain.json's two other viewpoints (golden_test.cpp's
// terrain_overview and terrain_low_sun cases, which the culling and deferred-terrain
// tests draw again) and where a failed comparison leaves its two images.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iterator>
#include <string>
#include <tuple>

#include <glm/glm.hpp>

#include <gtest/gtest.h>

#include "app/runner.h"
#include "asset/scene_desc.h"
#include "core/image.h"
#include "../support/no_undeclared_uniforms.h"

namespace engine::test {

// The terrain's second viewpoint: high above, looking over the valley to the
// mountains, where coarse LOD levels and the morph between them show.
inline void useTerrainOverview(SceneDesc& scene) {
  scene.camera.position = glm::dvec3(800.0, 650.0, 1500.0);
  scene.camera.forward = glm::normalize(glm::dvec3(0.0, -450.0, -1500.0));
}

// The valley at a low sun from the left: the mountains on that side shade the
// valley and the robots in it (near and far sun maps, the terrain casting) while
// the far slopes facing the sun stay lit.
inline void useTerrainLowSun(SceneDesc& scene) {
  scene.lights[0].direction = glm::normalize(glm::dvec3(-0.95, 0.2, 0.2));
}

// sky.json's sun at `degrees` above the horizon, its azimuth kept (25 degrees right
// of the view).
inline void useSunElevation(SceneDesc& scene, double degrees) {
  const glm::dvec3 d = scene.lights[0].direction;
  const glm::dvec3 across = glm::normalize(glm::dvec3(d.x, 0.0, d.z));
  const double e = glm::radians(degrees);
  scene.lights[0].direction = across * std::cos(e) + glm::dvec3(0.0, std::sin(e), 0.0);
}

// `game`'s frame at `time` as golden_test.cpp draws it: 640x360, the third frame of
// a still camera (the sun maps' kept path), GL debug output on; empty on failure.
// `afterFrames` runs while the game's GL objects still exist (runHeadless's).
inline Image goldenFrame(Backend backend, Game& game, double time, const std::function<void()>& afterFrames = {}) {
  RunOptions run;
  run.width = 640;
  run.height = 360;
  run.time = time;
  run.frames = 3;
  run.debugGl = true;
  Image image;
  auto status = runHeadless(backend, game, run, &image, afterFrames);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return image;
}

// How far two images of one size are apart: the largest difference of a channel,
// in levels, and how many channels differ at all.
struct ChannelDifference {
  int largest = 0;
  std::size_t differing = 0;
};
inline ChannelDifference channelDifference(const Image& a, const Image& b) {
  ChannelDifference d;
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    const int level = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    d.largest = std::max(d.largest, level);
    d.differing += level != 0;
  }
  return d;
}

// Two images that should have agreed, as build/golden-failures/STEM_A.png and
// STEM_B.png, to be looked at.
inline void writeFailurePair(const std::string& stem, const std::string& nameA, const Image& a,
                             const std::string& nameB, const Image& b) {
  const std::filesystem::path out = std::filesystem::path(ENGINE_BINARY_DIR) / "golden-failures";
  std::filesystem::create_directories(out);
  (void)writePng((out / (stem + "_" + nameA + ".png")).string(), a);
  (void)writePng((out / (stem + "_" + nameB + ".png")).string(), b);
}

// A golden comparison over both backends and each case of a table (a param of
// (backend, index into `cases`), each case with a `name`): GoldenScenes/Suite/egl_NAME.
#define ENGINE_INSTANTIATE_GOLDEN_CASES_ON(Suite, cases, ...)                                   \
  INSTANTIATE_TEST_SUITE_P(                                                                     \
      GoldenScenes, Suite,                                                                      \
      ::testing::Combine(::testing::Values(__VA_ARGS__), ::testing::Range(0, int(std::size(cases)))), \
      [](const ::testing::TestParamInfo<std::tuple<::engine::Backend, int>>& p) {               \
        return std::string(::engine::backendName(std::get<0>(p.param))) + "_" +                 \
               cases[std::get<1>(p.param)].name;                                                \
      })
#define ENGINE_INSTANTIATE_GOLDEN_CASES(Suite, cases) \
  ENGINE_INSTANTIATE_GOLDEN_CASES_ON(Suite, cases, ::engine::Backend::Egl, ::engine::Backend::OsMesa)
// EGL alone, for a table whose test compares two frames drawn in one context
// (culled against unculled, deferred against forward): tests/support/gl_test.h's
// ENGINE_INSTANTIATE_OFFSCREEN_EGL says why.
#define ENGINE_INSTANTIATE_GOLDEN_CASES_EGL(Suite, cases) \
  ENGINE_INSTANTIATE_GOLDEN_CASES_ON(Suite, cases, ::engine::Backend::Egl)

}  // namespace engine::test
