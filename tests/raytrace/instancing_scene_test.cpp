// EXT_mesh_gpu_instancing through the scene layer: the tracer's scene holds one
// mesh per instance of SimpleInstancing (../shared/gltf-samples), placed as the pose
// dump places them (node world * instance), rays from in front of the grid hit the
// front layer's boxes where they stand, and the culling bounds hold every instance.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "scene/model_asset.h"

namespace engine::rt {
namespace {

const std::string kFolder = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/SimpleInstancing/glTF-Binary/";

class RtInstancing : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kFolder + "SimpleInstancing.glb")) GTEST_SKIP() << kFolder << " not found";
    auto desc = parseScene(R"({"models": [{"path": "SimpleInstancing.glb"}]})", kFolder + "instancing.json");
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    auto scene = AnimatedRtScene::create(*desc, 0.0);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    scene_ = std::make_unique<AnimatedRtScene>(std::move(scene).value());
    auto model = loadGltf(kFolder + "SimpleInstancing.glb");
    ASSERT_TRUE(model.ok()) << model.error().message;
    model_ = std::move(model).value();
  }
  std::unique_ptr<AnimatedRtScene> scene_;
  ModelData model_;
};

TEST_F(RtInstancing, EveryInstanceIsATracedMeshWhereThePoseDumpPutsIt) {
  const auto& meshes = scene_->scene().meshes();
  ASSERT_EQ(meshes.size(), 125u);
  auto pose = dumpPose(model_, -1, 0.0);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  ASSERT_EQ((*pose)["meshes"].size(), 125u);
  double worst = 0.0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const auto& expected = (*pose)["meshes"][m]["positions"];
    ASSERT_EQ(meshes[m].positions.size() * 3, expected.size());
    for (std::size_t v = 0; v < meshes[m].positions.size(); ++v) {
      const glm::dvec3 e(expected[3 * v].get<double>(), expected[3 * v + 1].get<double>(), expected[3 * v + 2].get<double>());
      worst = std::max(worst, glm::length(glm::dvec3(meshes[m].positions[v]) - e));
    }
  }
  EXPECT_LE(worst, 1e-5);
}

// The 25 instances of the front layer (translation z = 10) face +z unhidden: a ray
// down -z through each one's centre hits that box, within its half diagonal.
TEST_F(RtInstancing, RaysFromTheFrontHitTheFrontLayersBoxes) {
  const auto& instances = model_.nodes[0].instances;
  ASSERT_EQ(instances.size(), 125u);
  int front = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const glm::vec3 center = glm::vec3(instances[i] * glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));  // the cube spans [0, 1]
    if (std::abs(instances[i][3].z - 10.0f) > 1e-4f) continue;
    ++front;
    const Ray<double> ray{glm::dvec3(center.x, center.y, 100.0), glm::dvec3(0.0, 0.0, -1.0)};
    const auto hit = scene_->scene().intersect(ray);
    ASSERT_TRUE(hit.has_value()) << "instance " << i;
    const glm::mat3 axes(instances[i]);  // the scaled cube's edges: scale is not uniform
    const double halfDiagonal = 0.5 * std::sqrt(glm::dot(axes[0], axes[0]) + glm::dot(axes[1], axes[1]) +
                                                glm::dot(axes[2], axes[2]));
    EXPECT_LE(glm::distance(hit->p, glm::dvec3(center)), halfDiagonal + 1e-6) << "instance " << i;
  }
  EXPECT_EQ(front, 25);
}

TEST_F(RtInstancing, CullingBoundsHoldEveryInstance) {
  auto asset = ModelAsset::create(model_);
  ASSERT_TRUE(asset.ok()) << asset.error().message;
  auto bounds = (*asset)->boundsOfAllPoses();
  ASSERT_TRUE(bounds.ok()) << bounds.error().message;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const RtMesh& mesh : scene_->scene().meshes())
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(bounds->min[k], lo[k], 1e-5);
    EXPECT_NEAR(bounds->max[k], hi[k], 1e-5);
  }
  EXPECT_GT(hi.x, 10.0f);  // the last instance reaches past (10, 10, 10)
}

}  // namespace
}  // namespace engine::rt
