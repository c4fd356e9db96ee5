// One terrain for every renderer (scene/terrain_mesh.h): the tracer's triangles of
// a view hold every triangle the rasterizer drew for it, vertex for vertex, at the
// scene file's LOD target and under the renderer's override (the trade panel's
// knob, demo --terrain-error), where the tracer once triangulated the file's
// target alone.
#include <gtest/gtest.h>

#include <array>
#include <set>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"
#include "scene/scene.h"
#include "scene/terrain_mesh.h"
#include "terrain/page_pool.h"
#include "terrain/terrain.h"
#include "terrain/terrain_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

class TerrainViews : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(TerrainViews);

using Triangle = std::array<float, 9>;

std::set<Triangle> trianglesOf(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  std::set<Triangle> out;
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = positions[indices[i + std::size_t(k)]];
      t[std::size_t(3 * k)] = p.x, t[std::size_t(3 * k + 1)] = p.y, t[std::size_t(3 * k + 2)] = p.z;
    }
    out.insert(t);
  }
  return out;
}

struct TerrainFrame {
  std::set<Triangle> raster, traced;
};

// One frame of terrain.json at `width` x `height` rasterized, and the tracer's
// scene of the same view, both with LOD override `errorOverride` (0: the file's).
TerrainFrame terrainFrame(int width, int height, double errorOverride) {
  TerrainFrame out;
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/terrain.json");
  EXPECT_TRUE(desc.ok()) << desc.error().message;
  if (!desc) return out;
  auto scene = Scene::load(*desc);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return out;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.iblSizeOverride = 16;  // the ambient does not change the terrain
  options.terrainErrorOverride = errorOverride;
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return out;
  auto target = RenderTarget::create(width, height, 1);
  EXPECT_TRUE(target.ok());
  if (!target) return out;
  target->bind();
  EXPECT_TRUE((*renderer)->update(0.0).ok());
  const Camera camera = (*renderer)->initialCamera();
  const Status frame = (*renderer)->render(camera, width, height);
  EXPECT_TRUE(frame.ok()) << frame.error().message;
  const terrain::LodSelection* drawn = (*renderer)->mainTerrainSelection();
  EXPECT_NE(drawn, nullptr);
  if (!drawn) return out;
  EXPECT_EQ((*renderer)->stats().terrainViewportHeight, height);
  for (const TerrainPatchMesh& patch : terrainPatchMeshes(*(*scene)->terrain(), *drawn, camera.position)) {
    out.raster.merge(trianglesOf(patch.positions, terrainPatchIndices()));
  }
  auto built = rt::AnimatedRtScene::create(*scene, height, nullptr, nullptr, errorOverride);
  EXPECT_TRUE(built.ok()) << built.error().message;
  if (!built) return out;
  const rt::RtScene& rtScene = built->scene();
  for (const rt::RtMesh& mesh : rtScene.meshes()) {
    if (rtScene.materials()[std::size_t(mesh.material)].name != "terrain") continue;
    out.traced.merge(trianglesOf(mesh.positions, mesh.indices));
  }
  return out;
}

std::size_t missingFrom(const std::set<Triangle>& drawn, const std::set<Triangle>& traced) {
  std::size_t missing = 0;
  for (const Triangle& t : drawn) missing += traced.count(t) == 0 ? 1 : 0;
  return missing;
}

}  // namespace

// The tracer's terrain is unculled (what lies outside the view still shadows it),
// so it holds more triangles than the frame drew; every one drawn is among them,
// with the same vertices, at the file's target and under coarser and finer
// overrides. The overrides change the triangles, so the test sees the knob.
TEST_P(TerrainViews, TheTracerTracesTheTerrainTheRasterizerDraws) {
  std::size_t fileTarget = 0;
  for (const double errorOverride : {0.0, 1.0, 8.0}) {
    SCOPED_TRACE(errorOverride);
    const TerrainFrame f = terrainFrame(192, 108, errorOverride);
    ASSERT_GT(f.raster.size(), 1000u);
    EXPECT_GE(f.traced.size(), f.raster.size());
    EXPECT_EQ(missingFrom(f.raster, f.traced), 0u) << "of " << f.raster.size() << " drawn triangles";
    if (errorOverride == 0.0) fileTarget = f.traced.size();
    else EXPECT_NE(f.traced.size(), fileTarget) << "the override did not reach the tracer";
  }
}

// The tracer selects within the page budget of the rasterizer's default pool, worked
// out without GL (terrain/page_pool.h): the same number of slots as the GL pool.
TEST_P(TerrainViews, TheTracersPageBudgetIsTheRasterizersPool) {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/terrain.json");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto scene = Scene::load(*desc);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  auto renderer = terrain::TerrainRenderer::create(test::shaderDir(), *(*scene)->terrain(), {});
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  EXPECT_EQ(renderer->pageSlots(), terrain::defaultPageSlots());
}
