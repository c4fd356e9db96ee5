// The terrain patches an opaque plane hides are left out (render/plane_occlusion.h)
// and the frame is the same bytes: demo.json, whose plaza hides the valley floor,
// with and without GPU culling; a margin that hides what shows moves the image.
#include <gtest/gtest.h>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

class PlaneOcclusion : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(PlaneOcclusion);

struct Frame {
  Image image;
  SceneStats stats;
};

Frame demoFrame(bool occlusion, bool gpuCulling, double pixelMargin = cull::kPlanePixelMargin) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/demo.json");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.iblSizeOverride = 16;  // the ambient's size does not change what is culled
  options.planeOcclusion = occlusion;
  options.planeOcclusionPixelMargin = pixelMargin;
  options.gpuCullingOverride = gpuCulling;
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  auto target = RenderTarget::create(480, 270, 1);
  EXPECT_TRUE(target.ok());
  if (!target) return {};
  target->bind();
  EXPECT_TRUE((*renderer)->update(0.5).ok());
  const Status frame = (*renderer)->render((*renderer)->initialCamera(), 480, 270);
  EXPECT_TRUE(frame.ok()) << frame.error().message;
  return {target->readPixels(), (*renderer)->stats()};
}

}  // namespace

TEST_P(PlaneOcclusion, HiddenPatchesLeftOutTheSameBytes) {
  for (bool gpuCulling : {false, true}) {
    SCOPED_TRACE(gpuCulling ? "gpu culling" : "no gpu culling");
    const Frame all = demoFrame(false, gpuCulling), occluded = demoFrame(true, gpuCulling);
    EXPECT_EQ(all.stats.terrainPatchesHidden, 0);
    // Measured: 14 of 62 patches, 28,672 of 126,976 triangles at 1280x720.
    EXPECT_GT(occluded.stats.terrainPatchesHidden, 5);
    EXPECT_LT(occluded.stats.terrainTriangles, all.stats.terrainTriangles);
    ASSERT_EQ(all.image.pixels.size(), occluded.image.pixels.size());
    EXPECT_TRUE(all.image.pixels == occluded.image.pixels);
  }
}

// The test can fail: a margin 40 pixels the wrong way hides the patches that show
// over the plaza's far edge, and holes open in the hills.
TEST_P(PlaneOcclusion, AMarginThatHidesWhatShowsMovesTheImage) {
  const Frame all = demoFrame(false, false), wrong = demoFrame(true, false, -40.0);
  EXPECT_GT(wrong.stats.terrainPatchesHidden, demoFrame(true, false).stats.terrainPatchesHidden);
  EXPECT_FALSE(all.image.pixels == wrong.image.pixels);
}
