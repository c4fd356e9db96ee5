// The scene renderer's passes over sorted draw items (render/draw_items.h): on
// every shipped scene each pass binds each of its programs once, and a frame
// leaves GL's state as render/pass_state.h says, whatever the passes set.
#include <gtest/gtest.h>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

class DrawItems : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(DrawItems);

SceneStats statsOfOneFrame(const std::string& file) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + file);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.iblSizeOverride = 16;  // the ambient's size does not change the draws
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  auto target = RenderTarget::create(160, 90, 1);
  EXPECT_TRUE(target.ok());
  if (!target) return {};
  target->bind();
  EXPECT_TRUE((*renderer)->update(0.7).ok());
  const Status frame = (*renderer)->render((*renderer)->initialCamera(), 160, 90);
  EXPECT_TRUE(frame.ok()) << frame.error().message;
  return (*renderer)->stats();
}

}  // namespace

// The draws of demo.json (four robots of several primitives, shapes, two shadow
// maps) come in fewer programs than draws; sorted by program, each pass binds
// each once. In the order they are collected, demo.json binds 9 (against 7) and
// materials.json 10 (against 9).
TEST_P(DrawItems, EachPassBindsEachOfItsProgramsOnce) {
  for (const char* file : {"demo.json", "cornell.json", "materials.json", "terrain.json"}) {
    SCOPED_TRACE(file);
    const SceneStats stats = statsOfOneFrame(file);
    EXPECT_GT(stats.drawCalls, 0);
    EXPECT_GT(stats.programsNeeded, 0);
    EXPECT_EQ(stats.programChanges, stats.programsNeeded);
  }
}

// After a frame the caller gets GL's usual state back (render/pass_state.h's
// kCallerState), whatever the frame's last pass was: depth test on with LESS,
// depth writes on, culling on, no blending, no offset, no clamp.
TEST_P(DrawItems, AFrameLeavesTheCallersState) {
  for (const char* file : {"materials.json", "terrain.json"}) {
    SCOPED_TRACE(file);
    statsOfOneFrame(file);
    GLint func = 0, mask = 0, front = 0;
    glGetIntegerv(GL_DEPTH_FUNC, &func);
    glGetIntegerv(GL_DEPTH_WRITEMASK, &mask);
    glGetIntegerv(GL_FRONT_FACE, &front);
    EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_EQ(func, GL_LESS);
    EXPECT_EQ(mask, GL_TRUE);
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
    EXPECT_EQ(front, GL_CCW);
    EXPECT_FALSE(glIsEnabled(GL_BLEND));
    EXPECT_FALSE(glIsEnabled(GL_POLYGON_OFFSET_FILL));
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_CLAMP));
  }
}
