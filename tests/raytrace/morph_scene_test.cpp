// The ray tracer's models morph as the pose dump does (the path the conformance
// poses check against three.js): every mesh of a scene holding the repository's
// morph test model equals the dumped world positions, at creation and after
// setTime, for STEP, LINEAR and CUBICSPLINE weights and a skinned, morphed mesh.
#include <gtest/gtest.h>

#include <string>

#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"

namespace engine::rt {
namespace {

const std::string kFolder = std::string(ENGINE_SOURCE_DIR) + "/tests/conformance/morph_poses/";

// Largest distance between the scene's model meshes and the dump's positions, in
// the dump's order (nodes, then primitives: the order poseInstance adds meshes).
double largestDistance(const RtScene& scene, const nlohmann::json& pose) {
  double worst = 0.0;
  std::size_t mesh = 0;
  for (const auto& entry : pose["meshes"]) {
    const auto& expected = entry["positions"];
    const auto& got = scene.meshes().at(mesh++).positions;
    EXPECT_EQ(got.size() * 3, expected.size());
    for (std::size_t v = 0; v < got.size() && 3 * v + 2 < expected.size(); ++v) {
      const glm::dvec3 e(expected[3 * v].get<double>(), expected[3 * v + 1].get<double>(),
                         expected[3 * v + 2].get<double>());
      worst = std::max(worst, glm::length(glm::dvec3(got[v]) - e));
    }
  }
  return worst;
}

TEST(RtMorph, ModelMeshesMatchThePoseDump) {
  auto model = loadGltf(kFolder + "MorphInterpolation.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  for (int clip = 0; clip < 3; ++clip) {
    SCOPED_TRACE("clip " + std::to_string(clip));
    const std::string text = R"({"models": [{"path": "MorphInterpolation.gltf", "clip": )" + std::to_string(clip) + "}]}";
    auto desc = parseScene(text, kFolder + "morph.json");
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    auto scene = AnimatedRtScene::create(*desc, 0.5);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->scene().meshes().size(), 3u);  // two quads and the skinned strip
    auto pose = dumpPose(*model, clip, 0.5);
    ASSERT_TRUE(pose.ok()) << pose.error().message;
    EXPECT_LE(largestDistance(scene->scene(), *pose), 1e-6);
    for (double t : {1.25, 1.75}) {
      ASSERT_TRUE(scene->setTime(t).ok());
      auto moved = dumpPose(*model, clip, t);
      ASSERT_TRUE(moved.ok()) << moved.error().message;
      EXPECT_NE((*moved)["meshes"][1]["positions"], (*pose)["meshes"][1]["positions"]) << "the weights did not move";
      EXPECT_LE(largestDistance(scene->scene(), *moved), 1e-6) << t;
    }
  }
}

}  // namespace
}  // namespace engine::rt
