// Reflection probes of a static scene are drawn once and kept; what they show must
// not depend on where the camera was when they were drawn.
#include <gtest/gtest.h>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// A mirror sphere on a ground plane, a box beside it whose sun shadow falls
// where the mirror sees it, and nothing that moves: the probe is drawn once.
constexpr const char* kMirrorScene = R"({
  "camera": {"position": [0, 2, 7], "target": [0, 1, 0], "far": 2000},
  "materials": {"ground": {"color": [0.8, 0.8, 0.8]}, "box": {"color": [0.7, 0.3, 0.2]},
                "mirror": {"color": [1, 1, 1], "reflection": 0.9}},
  "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "extent": 40, "material": "ground"},
                 {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "mirror"},
                 {"type": "box", "min": [1.8, 0, -0.6], "max": [2.6, 2.5, 0.6], "material": "box"}],
  "lights": [{"type": "sun", "direction": [0.8, 1, 0.3], "intensity": 3, "shadows": true}]
})";

Camera cameraAt(const glm::dvec3& position, const glm::dvec3& target) {
  Camera camera;
  camera.position = position;
  camera.farPlane = 2000.0;
  camera.lookAt(target);
  return camera;
}

Image renderFrames(SceneRenderer& renderer, const std::vector<Camera>& cameras) {
  auto target = RenderTarget::create(160, 120, 1);
  EXPECT_TRUE(target.ok());
  for (const Camera& camera : cameras) {
    target->bind();
    auto status = renderer.render(camera, 160, 120);
    EXPECT_TRUE(status.ok()) << status.error().message;
  }
  return target->readPixels();
}

}  // namespace

class Probes : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(Probes);

// The camera first looks at empty ground 300 m away (its sun map then covers none
// of the mirror's surroundings), then at the mirror. The mirror must show the box's
// shadow as a renderer that only ever saw the second view draws it: bit for bit.
TEST_P(Probes, StaticProbesDoNotKeepTheFirstCamerasShadows) {
  auto scene = parseScene(kMirrorScene, "mirror.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  const Camera away = cameraAt({300, 2, 300}, {320, 0, 320});
  const Camera near = cameraAt({0, 2, 7}, {0, 1, 0});

  auto moved = SceneRenderer::create(*scene, options);
  ASSERT_TRUE(moved.ok()) << moved.error().message;
  ASSERT_TRUE((*moved)->update(0.0).ok());
  const Image afterMoving = renderFrames(**moved, {away, near});

  auto fresh = SceneRenderer::create(*scene, options);
  ASSERT_TRUE(fresh.ok()) << fresh.error().message;
  ASSERT_TRUE((*fresh)->update(0.0).ok());
  const Image direct = renderFrames(**fresh, {near});

  ASSERT_EQ(afterMoving.pixels.size(), direct.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < direct.pixels.size(); ++i) differing += afterMoving.pixels[i] != direct.pixels[i];
  EXPECT_EQ(differing, 0u) << "the probe kept the shadows of the camera it was drawn from";
}
