// The scene's environment (scene/environment.h): the scene file's lights first, then
// each model instance's KHR_lights_punctual placed by its instance; the first sun
// is the sun; and the tracers take their lights from it, not from the scene file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "scene/scene.h"

namespace engine {
namespace {

const std::string kLamp = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf";

// A sun, a point light, and the Khronos lamp (five point lights) twice: once at
// (10, 0, 0), once turned 90 degrees about y at (0, 0, -4) and scaled by 2.
Result<SceneDesc> lampScene() {
  return parseScene(R"({
    "lights": [
      {"type": "point", "position": [0, 3, 0], "color": [1, 1, 1], "intensity": 2},
      {"type": "sun", "direction": [0, 1, 1], "color": [1, 1, 1], "intensity": 1},
      {"type": "sun", "direction": [1, 1, 0], "color": [1, 0, 0], "intensity": 1}
    ],
    "models": [
      {"path": ")" + kLamp + R"(", "position": [10, 0, 0]},
      {"path": ")" + kLamp + R"(", "position": [0, 0, -4], "rotation": [0, 90, 0], "scale": 2}
    ]})",
                    "lamp.json");
}

TEST(SceneEnvironment, ModelsLightsFollowTheFilesPlacedByTheirInstances) {
  if (!std::filesystem::exists(kLamp)) GTEST_SKIP() << kLamp << " not found";
  auto desc = lampScene();
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto scene = Scene::load(*desc);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const SceneEnvironment& environment = (*scene)->environment();
  ASSERT_EQ(environment.lights.size(), 3u + 2u * 5u);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(environment.lights[i].position, desc->lights[i].position) << i;
  // The lamp's first light node stands at (0.0462, 0.9078, 0.0067) in the model.
  const glm::dvec3 first(0.04622355476021767, 0.9077973365783693, 0.006696629337966442);
  const LightDesc& a = environment.lights[3];
  EXPECT_EQ(a.type, LightType::Point);
  EXPECT_TRUE(a.falloff);
  EXPECT_FALSE(a.shadows);
  EXPECT_NEAR(glm::length(a.position - (first + glm::dvec3(10.0, 0.0, 0.0))), 0.0, 1e-9);
  EXPECT_FLOAT_EQ(a.intensity, 15.0f);  // candela, as the file gives it
  // Turned about y by 90 degrees (x -> -z, z -> x), scaled by 2, moved.
  const LightDesc& b = environment.lights[3 + 5];
  const glm::dvec3 turned(2.0 * first.z, 2.0 * first.y, -2.0 * first.x);
  EXPECT_NEAR(glm::length(b.position - (turned + glm::dvec3(0.0, 0.0, -4.0))), 0.0, 1e-9);
  // The sun is the first of the file's two.
  ASSERT_NE(environment.sun(), nullptr);
  EXPECT_EQ(environment.sun(), &environment.lights[1]);
  EXPECT_EQ(*environment.sunDirection(), glm::normalize(glm::vec3(desc->lights[1].direction)));
}

TEST(SceneEnvironment, TheTracersLightsAreTheEnvironments) {
  if (!std::filesystem::exists(kLamp)) GTEST_SKIP() << kLamp << " not found";
  auto desc = lampScene();
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto scene = Scene::load(*desc);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  auto rt = rt::AnimatedRtScene::create(*scene);
  ASSERT_TRUE(rt.ok()) << rt.error().message;
  const std::vector<LightDesc>& traced = rt->scene().lights();
  const std::vector<LightDesc>& lights = (*scene)->environment().lights;
  ASSERT_EQ(traced.size(), lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    EXPECT_EQ(traced[i].type, lights[i].type) << i;
    EXPECT_EQ(traced[i].position, lights[i].position) << i;
    EXPECT_EQ(traced[i].direction, lights[i].direction) << i;
    EXPECT_EQ(traced[i].color * traced[i].intensity, lights[i].color * lights[i].intensity) << i;
  }
}

// Without models the environment is the file's lights and sky, its image the one
// decoded with the scene's images.
TEST(SceneEnvironment, WithoutModelsItIsTheFilesLightsAndSky) {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto scene = Scene::load(*desc);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const SceneEnvironment& environment = (*scene)->environment();
  ASSERT_EQ(environment.lights.size(), desc->lights.size());
  for (size_t i = 0; i < desc->lights.size(); ++i) EXPECT_EQ(environment.lights[i].position, desc->lights[i].position);
  EXPECT_EQ(environment.sky.enabled, desc->sky.enabled);
  EXPECT_EQ(environment.skyImage, (*scene)->images().sky);
}

}  // namespace
}  // namespace engine
