// A small scene at the origin and the same scene moved 1e5 m away must render the
// same image: camera-relative drawing (offsets taken in double) and reverse-Z
// float depth keep float precision where the camera is, not where the origin is.
#include <gtest/gtest.h>

#include "app/runner.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "scene_game.h"

using namespace engine;

namespace {

SceneDesc translated(SceneDesc scene, const glm::dvec3& offset) {
  scene.camera.position += offset;
  for (auto& l : scene.lights) l.position += offset;
  for (auto& p : scene.primitives) {
    p.center += offset;
    p.point += offset;
    p.min += offset;
    p.max += offset;
  }
  for (auto& m : scene.models) m.position += offset;
  scene.terrain.origin += offset;
  return scene;
}

Image render(const SceneDesc& scene) {
  SceneRenderOptions options;
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  demo::SceneGame game(scene, options);
  RunOptions run;
  run.width = 320;
  run.height = 240;
  run.debugGl = true;
  Image image;
  EXPECT_TRUE(runHeadless(Backend::Egl, game, run, &image).ok());
  return image;
}

}  // namespace

TEST(FarFromOrigin, CornellRoomAt1e5MetresLooksTheSame) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Image near = render(*scene);
  const Image far = render(translated(*scene, glm::dvec3(1e5, 0.0, 1e5)));
  auto diff = compareImages(near, far, 8);
  ASSERT_TRUE(diff.ok());
  std::printf("origin vs 1e5 m: mean %.4f, max %d, %.4f%% over 8\n", diff->meanAbs, diff->maxAbs, diff->shareOver * 100);
  // A float world position at 1e5 m has a 7.8 mm step; drawn world-relative, the
  // walls would shimmer and the spheres' silhouettes move by pixels. Camera-relative
  // (offsets taken in double before anything becomes float) the images are
  // identical here; the limits allow a few rounding-level edge pixels.
  EXPECT_LT(diff->shareOver, 0.002);
  EXPECT_LT(diff->meanAbs, 0.1);
}

TEST(FarFromOrigin, DemoSceneAt1e5MetresLooksTheSame) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/demo.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Image near = render(*scene);
  const Image far = render(translated(*scene, glm::dvec3(1e5, 0.0, -1e5)));
  auto diff = compareImages(near, far, 8);
  ASSERT_TRUE(diff.ok());
  std::printf("demo origin vs 1e5 m: mean %.4f, max %d, %.4f%% over 8\n", diff->meanAbs, diff->maxAbs,
              diff->shareOver * 100);
  // Skinned robots, terrain and sun shadows too. The shadow map's texel grid is
  // snapped in world space, so it sits differently against the scene 1e5 m away:
  // shadow edges may move by a texel (a fraction of a percent of the pixels).
  EXPECT_LT(diff->shareOver, 0.01);
  EXPECT_LT(diff->meanAbs, 0.5);
}
