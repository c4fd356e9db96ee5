// The scene layer (scene/scene.h): what the rasterizer and the tracers both draw.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <set>

#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "scene/instances.h"
#include "scene/scene.h"

namespace engine {
namespace {

const std::string kScenes = std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/";

std::shared_ptr<Scene> loadScene(const SceneDesc& desc) {
  auto scene = Scene::load(desc);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? *scene : nullptr;
}

SceneDesc demo() {
  auto desc = loadSceneFile(kScenes + "demo.json");
  EXPECT_TRUE(desc.ok()) << desc.error().message;
  return desc.ok() ? *desc : SceneDesc{};
}

double largestJointDifference(const Pose& a, const Pose& b) {
  double worst = 0.0;
  for (size_t j = 0; j < a.joints.size(); ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) worst = std::max(worst, double(std::abs(a.joints[j][c][r] - b.joints[j][c][r])));
  return worst;
}

// demo.json places four robots from one file: one asset, four instances on it.
TEST(Scene, LoadsEachModelFileOnce) {
  const SceneDesc desc = demo();
  auto scene = loadScene(desc);
  ASSERT_TRUE(scene);
  std::set<std::string> paths;
  for (const ModelDesc& m : desc.models) paths.insert(m.path);
  ASSERT_EQ(scene->instances().size(), desc.models.size());
  EXPECT_EQ(scene->assets().size(), paths.size());
  for (size_t i = 0; i < desc.models.size(); ++i)
    EXPECT_EQ(scene->assetOf(scene->instances()[i]).model.path, desc.models[i].path) << i;
}

// A pose depends on the scene time alone: going elsewhere and coming back gives
// the same bytes, and they are samplePose's at the instance's clip time.
TEST(Scene, PoseIsAFunctionOfTimeAlone) {
  auto scene = loadScene(demo());
  ASSERT_TRUE(scene);
  ASSERT_TRUE(scene->update(1.7).ok());
  std::vector<Pose> first;
  for (const ModelInstance& i : scene->instances()) first.push_back(i.pose);
  ASSERT_TRUE(scene->update(0.2).ok());
  EXPECT_GT(largestJointDifference(first[0], scene->instances()[0].pose), 1e-3) << "the walk did not move";
  ASSERT_TRUE(scene->update(1.7).ok());
  std::vector<Srt> locals;
  for (size_t k = 0; k < first.size(); ++k) {
    const ModelInstance& instance = scene->instances()[k];
    ASSERT_EQ(instance.pose.joints.size(), first[k].joints.size());
    EXPECT_EQ(std::memcmp(instance.pose.joints.data(), first[k].joints.data(),
                          first[k].joints.size() * sizeof(glm::mat4)),
              0)
        << k;
    Pose direct;
    ASSERT_TRUE(samplePose(scene->assetOf(instance), instance.clip, clipTimeAt(instance.desc, 1.7), locals, direct).ok());
    EXPECT_EQ(largestJointDifference(direct, instance.pose), 0.0) << k;
  }
}

// The instance's root never reaches the joints: the same clip at the same time
// gives the same model-space joints at the origin and a thousand kilometres
// away, turned and scaled, so far instances lose no precision before a view
// subtracts its eye from the root in double.
TEST(Scene, JointsAreInModelSpaceWhereverTheInstanceStands) {
  SceneDesc desc = demo();
  desc.models.resize(1);
  desc.models.push_back(desc.models[0]);
  desc.models[1].position = glm::dvec3(1.0e6, 250.0, -1.0e6);
  desc.models[1].rotationDegrees = glm::dvec3(0.0, 73.0, 0.0);
  desc.models[1].scale = glm::dvec3(2.5);
  auto scene = loadScene(desc);
  ASSERT_TRUE(scene);
  ASSERT_TRUE(scene->update(0.9).ok());
  const auto instances = scene->instances();
  EXPECT_EQ(largestJointDifference(instances[0].pose, instances[1].pose), 0.0);
  EXPECT_EQ(instances[1].world[3].x, 1.0e6);
  // The bounds' radius takes the scale.
  EXPECT_NEAR(instances[1].boundsRadius, 2.5 * instances[0].boundsRadius, 1e-9 * instances[1].boundsRadius);
}

// Far from time zero the clip wraps in double: 2000 random scene times up to
// 10^7 seconds pose as the same time folded into the first cycles does.
TEST(Scene, TimesFarFromZeroPoseAsTheirWrappedTime) {
  SceneDesc desc = demo();
  desc.models.resize(1);
  desc.models[0].start = 0.0;
  desc.models[0].speed = 1.0;
  auto far = loadScene(desc);
  auto near = loadScene(desc);
  ASSERT_TRUE(far && near);
  const double duration = far->assetOf(far->instances()[0]).animated.clips[size_t(far->instances()[0].clip)].duration();
  ASSERT_GT(duration, 0.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> phase(0.0, 1.0);
  std::uniform_int_distribution<long long> cycles(1, static_cast<long long>(1e7 / duration));
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double p = phase(rng) * duration;
    const double t = double(cycles(rng)) * duration + p;
    ASSERT_TRUE(far->update(t).ok());
    ASSERT_TRUE(near->update(std::fmod(t, duration)).ok());
    worst = std::max(worst, largestJointDifference(far->instances()[0].pose, near->instances()[0].pose));
  }
  // Both times go through the same fmod; what differs is only t's own rounding
  // (1e7 s carries 2e-9 s), far below a float joint's resolution.
  EXPECT_LE(worst, 1e-5);
}

// The viewer's way in: a model already in memory is used, not read again (its
// path names no file here), and a pose set from outside (a player's cross-fade)
// stands until an update at another time poses the clip again.
TEST(Scene, PreloadedModelsAndOutsidePoses) {
  auto source = ModelAsset::load(std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf");
  ASSERT_TRUE(source.ok()) << source.error().message;
  ModelData model = (*source)->model;
  model.path = "/nonexistent/in_memory.gltf";
  auto asset = ModelAsset::create(model);
  ASSERT_TRUE(asset.ok());
  SceneDesc desc;
  desc.path = "viewer";
  ModelDesc m;
  m.path = model.path;
  m.clip = "Walk";
  desc.models.push_back(m);
  EXPECT_FALSE(Scene::load(desc).ok()) << "the file exists after all";
  auto scene = Scene::load(desc, {*asset});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ((*scene)->assets().size(), 1u);
  EXPECT_EQ((*scene)->assets()[0].get(), asset->get()) << "the asset was copied or reloaded";
  ASSERT_TRUE((*scene)->update(0.5).ok());
  const Pose clipPose = (*scene)->instances()[0].pose;
  Pose rest;
  std::vector<Srt> locals;
  ASSERT_TRUE(samplePose(**asset, -1, 0.0, locals, rest).ok());
  ASSERT_GT(largestJointDifference(clipPose, rest), 1e-3);
  (*scene)->setPose(0, rest);
  ASSERT_TRUE((*scene)->update(0.5).ok());  // the same time: nothing re-posed
  EXPECT_EQ(largestJointDifference((*scene)->instances()[0].pose, rest), 0.0);
  ASSERT_TRUE((*scene)->update(0.6).ok());
  EXPECT_GT(largestJointDifference((*scene)->instances()[0].pose, rest), 1e-3);
}

// The rasterizer's nlerp knob poses the shared scene its way; the tracers' next
// update at the same time, with slerp (the truth), poses it back exactly.
TEST(Scene, NlerpPosesAreTheRasterizersAndSlerpComesBack) {
  auto scene = loadScene(demo());
  ASSERT_TRUE(scene);
  ASSERT_TRUE(scene->update(1.3).ok());
  const Pose slerp = scene->instances()[0].pose;
  ASSERT_TRUE(scene->update(1.3, QuatInterpolation::Nlerp).ok());
  const double moved = largestJointDifference(slerp, scene->instances()[0].pose);
  EXPECT_GT(moved, 0.0) << "nlerp posed nothing differently";
  EXPECT_LT(moved, 1e-2) << "nlerp strays further than a shortcut should";
  ASSERT_TRUE(scene->update(1.3).ok());
  EXPECT_EQ(largestJointDifference(slerp, scene->instances()[0].pose), 0.0);
}

TEST(Scene, AClipTheModelLacksNamesTheSceneFileAndElement) {
  SceneDesc desc = demo();
  desc.models[2].clip = "Moonwalk";
  auto scene = Scene::load(desc);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.error().message.find("demo.json: /models/2/clip: "), std::string::npos) << scene.error().message;
  EXPECT_NE(scene.error().message.find("Moonwalk"), std::string::npos) << scene.error().message;
}

// The tracer draws the scene layer's pose, not one of its own: setTime poses the
// shared scene, and the traced meshes follow it.
TEST(Scene, TheTracerSkinsTheSharedScenesPose) {
  // Without the terrain: its triangles are most of the tracer's build (21 s under
  // the sanitizers), and this is a question about the characters.
  SceneDesc desc = demo();
  desc.terrain.enabled = false;
  auto scene = loadScene(desc);
  ASSERT_TRUE(scene);
  ASSERT_TRUE(scene->update(0.4).ok());
  auto traced = rt::AnimatedRtScene::create(scene);
  ASSERT_TRUE(traced.ok()) << traced.error().message;
  auto positions = [](const rt::AnimatedRtScene& s) {
    std::vector<glm::vec3> all;
    for (const auto& mesh : s.scene().meshes()) all.insert(all.end(), mesh.positions.begin(), mesh.positions.end());
    return all;
  };
  const auto before = positions(*traced);
  ASSERT_TRUE(traced->setTime(1.3).ok());
  EXPECT_EQ(scene->time(), 1.3);
  const auto after = positions(*traced);
  ASSERT_EQ(before.size(), after.size());
  double moved = 0.0;
  for (size_t v = 0; v < before.size(); ++v) moved = std::max(moved, double(glm::length(after[v] - before[v])));
  EXPECT_GT(moved, 1e-2);
  // A tracer built afresh at 1.3 gives the same vertices bit for bit.
  auto fresh = rt::AnimatedRtScene::create(desc, 1.3);
  ASSERT_TRUE(fresh.ok()) << fresh.error().message;
  const auto expected = positions(*fresh);
  ASSERT_EQ(expected.size(), after.size());
  EXPECT_EQ(std::memcmp(expected.data(), after.data(), after.size() * sizeof(glm::vec3)), 0);
}

}  // namespace
}  // namespace engine
