// Levels of detail in the scene renderer (render.lod_pixels): fewer triangles where
// a level's measured error (ModelAsset::levelsOfDetail, in every sampled pose) is
// within the budget on screen, and a silhouette that moves by no more than that.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// Walking robots near, mid and far on a magenta background (nothing else is
// magenta), no shadows: what the characters cover is what differs from it.
constexpr const char* kLodScene = R"({
  "camera": {"position": [0, 1.6, 7], "target": [0, 1.0, 0], "fovy": 45},
  "lights": [{"type": "sun", "direction": [0.3, 1, 0.5], "intensity": 1.2, "shadows": false}],
  "models": [{"path": "%s", "position": [-1.5, 0, 0], "clip": %s},
             {"path": "%s", "position": [0.5, 0, -4], "clip": %s, "start": 0.3},
             {"path": "%s", "position": [2.5, 0, -12], "clip": %s, "start": 0.6}],
  "sky": {"enabled": false, "background": [1, 0, 1]},
  "render": {"shading": "classic", "tonemap": "none", "lod_pixels": %g}
})";

struct LodFrame {
  Image image;
  long long triangles = 0;
  std::string described;
};

LodFrame renderWithLod(const std::string& model, const char* clip, double lodPixels) {
  char text[4096];
  std::snprintf(text, sizeof text, kLodScene, model.c_str(), clip, model.c_str(), clip, model.c_str(), clip, lodPixels);
  auto scene = parseScene(text, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/lod.json");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  EXPECT_TRUE((*renderer)->update(1.0).ok());
  auto target = RenderTarget::create(640, 360, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  EXPECT_TRUE((*renderer)->render((*renderer)->initialCamera(), 640, 360).ok());
  return {target->readPixels(), (*renderer)->lastFrameTriangles(), (*renderer)->describe()};
}

bool covered(const Image& image, int x, int y) {
  const unsigned char* p = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
  return !(p[0] == 255 && p[1] == 0 && p[2] == 255);
}

// For every pixel that one image covers and the other does not: how far (in
// pixels, the larger axis) the full image's coverage of the other kind is. A
// silhouette that moved by d pixels gives d; a hole or a spike far from any edge
// gives more than `most`.
std::vector<int> silhouetteShifts(const Image& full, const Image& level, int most) {
  std::vector<int> counts(size_t(most) + 2, 0);
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) {
      const bool want = covered(level, x, y);
      if (covered(full, x, y) == want) continue;
      int found = most + 1;
      for (int r = 1; r <= most && found > most; ++r)
        for (int yy = std::max(0, y - r); yy <= std::min(full.height - 1, y + r) && found > most; ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(full.width - 1, x + r); ++xx)
            if (covered(full, xx, yy) == want) {
              found = r;
              break;
            }
      ++counts[size_t(found)];
    }
  return counts;
}

}  // namespace

class LevelsOfDetail : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(LevelsOfDetail);

// The shipped robot: boxy, so its levels are nearly free. A 1 px budget draws a
// quarter of the triangles, and every pixel whose coverage changes is next to the
// full image's silhouette (1 px of budget; measured: 4 pixels, all at 1).
TEST_P(LevelsOfDetail, FewerTrianglesAndTheSilhouetteWithinTheBudget) {
  const std::string robot = std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf";
  const LodFrame full = renderWithLod(robot, "\"Walk\"", 0.0), lod = renderWithLod(robot, "\"Walk\"", 1.0);
  EXPECT_EQ(full.described.find("lod("), std::string::npos) << full.described;
  EXPECT_NE(lod.described.find("lod(within 1 px: 7856 triangles >"), std::string::npos) << lod.described;
  EXPECT_LE(lod.triangles * 2, full.triangles);
  const std::vector<int> shifts = silhouetteShifts(full.image, lod.image, 1);
  EXPECT_EQ(shifts[2], 0) << "pixels whose coverage changed away from the silhouette";
  std::printf("robots: %lld of %lld triangles, %d pixels of coverage changed, all at the silhouette\n",
              lod.triangles, full.triangles, shifts[1]);
}

// CesiumMan (when ../shared has it): its levels err by more in a stride than in the
// rest pose (1.6 % of its size against 0.1 %: a level's triangle spans the bending
// knee), and the measure over poses is what keeps them away from the near figures.
// At 1 and 4 px the farther ones draw coarser, and the changed coverage lies
// within the budget + 1 px of the full image's silhouette but for pinholes where a
// thin part moved off what was behind it (measured at this view: none; allowed:
// 1 % of the changed pixels).
TEST_P(LevelsOfDetail, CesiumManWithinItsBudgetInMotion) {
  const std::string model =
      std::string(ENGINE_SOURCE_DIR) + "/../shared/conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << model << " is absent";
  const LodFrame full = renderWithLod(model, "0", 0.0);
  long long previous = full.triangles;
  for (const int budget : {1, 4}) {
    const LodFrame lod = renderWithLod(model, "0", double(budget));
    EXPECT_LT(lod.triangles, previous) << budget << " px";
    previous = lod.triangles;
    const std::vector<int> shifts = silhouetteShifts(full.image, lod.image, budget + 1);
    int changed = 0;
    for (int c : shifts) changed += c;
    std::printf("CesiumMan at %d px: %lld of %lld triangles, %d pixels of coverage changed, %d beyond %d px\n",
                budget, lod.triangles, full.triangles, changed, shifts.back(), budget + 1);
    EXPECT_GT(changed, 0);
    EXPECT_LE(shifts.back() * 100, changed);
  }
}
