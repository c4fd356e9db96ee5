// A pass's draws are sorted (render/draw_items.h), so what one draw leaves of the
// GL state must not change the draws after it. Found by the skin cache: a
// two-sided shape (every plane) turned face culling on in the point light's cube
// pass, which draws with culling off, so every caster drawn after it was culled
// one-sided: an open mesh facing away from the light lost its shadow. Here the
// morph strip (three open quads) casts onto a floor box, with and without a plane
// that draws first and is far behind everything: the images must be identical.
#include <gtest/gtest.h>

#include <string>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

std::string roomScene(bool farPlane) {
  const std::string plane =
      R"({"type": "plane", "point": [0, 0, 60], "normal": [0, 0, 1], "extent": 5, "material": "a_far"},)";
  return R"({
  "camera": {"position": [0, 4, 9], "target": [0, 0, 0], "far": 100},
  "materials": {"a_far": {"color": [0.2, 0.2, 0.2]}, "b_floor": {"color": [0.8, 0.8, 0.8]}},
  "primitives": [)" + (farPlane ? plane : std::string()) + R"(
    {"type": "box", "min": [-6, -0.5, -6], "max": [6, -0.2, 6], "material": "b_floor"}],
  "models": [{"path": "../../tests/conformance/morph_poses/MorphInterpolation.gltf", "position": [0, 0.4, 0]}],
  "lights": [{"type": "point", "position": [0.5, 4.0, -2.5], "intensity": 12, "shadows": true}]
})";
}

Image render(const std::string& text) {
  auto scene = parseScene(text, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/room.json");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  // Compute skinning draws the strip with the shapes' static program, after them
  // (draw_items.h: the models' materials follow the scene's).
  options.skinningOverride = Skinning::Compute;
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  EXPECT_TRUE((*renderer)->update(0.0).ok());
  auto target = RenderTarget::create(160, 120, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  const Status status = (*renderer)->render((*renderer)->initialCamera(), 160, 120);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return target->readPixels();
}

}  // namespace

class PassState : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(PassState);

TEST_P(PassState, PointShadowsDoNotDependOnWhatWasDrawnBefore) {
  const Image without = render(roomScene(false));
  const Image with = render(roomScene(true));
  ASSERT_EQ(without.pixels.size(), with.pixels.size());
  ASSERT_FALSE(without.pixels.empty());
  size_t differing = 0;
  for (size_t i = 0; i < without.pixels.size(); ++i) differing += without.pixels[i] != with.pixels[i];
  EXPECT_EQ(differing, 0u) << "a plane drawn first changed the shadows";
}
