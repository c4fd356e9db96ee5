// KHR_lights_punctual: the loader reads the file's lights and the nodes that place
// them; modelLights turns them into scene lights at their nodes' world transforms
// (LightsPunctualLamp from ../shared/gltf-samples, and small models written here),
// intensities as glTF gives them (lux, candela; see asset/model_lights.h). Bad
// lights are errors naming the file and the light or node.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "asset/gltf_loader.h"
#include "asset/model_lights.h"

namespace engine {
namespace {

using nlohmann::json;

const std::string kLamp = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf";

TEST(PunctualLights, TheLampsFivePointLightsStandAtTheirNodes) {
  if (!std::filesystem::exists(kLamp)) GTEST_SKIP() << kLamp << " not found";
  auto model = loadGltf(kLamp);
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->lights.size(), 5u);
  const json doc = json::parse(std::ifstream(kLamp));
  const auto lights = modelLights(*model);
  ASSERT_EQ(lights.size(), 5u);
  // Nodes 3..7 are roots with a matrix each, placing lights 0..4 in that order.
  for (std::size_t i = 0; i < 5; ++i) {
    SCOPED_TRACE("light " + std::to_string(i));
    const json& node = doc["nodes"][3 + i];
    const json& light = doc["extensions"]["KHR_lights_punctual"]["lights"][node["extensions"]["KHR_lights_punctual"]["light"].get<std::size_t>()];
    EXPECT_EQ(lights[i].type, LightType::Point);
    EXPECT_TRUE(lights[i].falloff);
    EXPECT_FALSE(lights[i].shadows);
    EXPECT_FLOAT_EQ(lights[i].intensity, light["intensity"].get<float>());  // candela, as it is
    const glm::vec3 color = light.contains("color") ? glm::vec3(light["color"][0].get<float>(), light["color"][1].get<float>(),
                                                                light["color"][2].get<float>())
                                                    : glm::vec3(1.0f);
    EXPECT_EQ(lights[i].color, color);
    const glm::dvec3 at(node["matrix"][12].get<double>(), node["matrix"][13].get<double>(), node["matrix"][14].get<double>());
    EXPECT_LT(glm::distance(lights[i].position, at), 1e-6);
  }
}

// A model of nothing but nodes and lights, loaded from memory as `name`.
Result<ModelData> lightsModel(const json& lights, const json& nodes, const std::string& name = "lights.gltf") {
  json doc{{"asset", {{"version", "2.0"}}},
           {"extensionsUsed", {"KHR_lights_punctual"}},
           {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}},
           {"nodes", nodes},
           {"scenes", {{{"nodes", json::array()}}}},
           {"scene", 0}};
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (!nodes[i].contains("parentless")) doc["scenes"][0]["nodes"].push_back(i);
  const std::string text = doc.dump();
  return loadGltfFromMemory(std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(text.data()), text.size()), name);
}

json lightNode(int light) { return json{{"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}}; }

TEST(PunctualLights, ADirectionalLightShinesAlongItsNodesMinusZ) {
  // Turned -90 degrees about x: the light's -Z becomes -Y, it shines straight down;
  // under a parent that moves it (a sun has no position) and doubles its size.
  json child = lightNode(0);
  child["rotation"] = {-0.7071068, 0.0, 0.0, 0.7071068};
  json parent{{"translation", {5, 5, 5}}, {"scale", {2, 2, 2}}, {"children", {1}}};
  auto model = lightsModel(json::array({{{"type", "directional"}, {"intensity", 3.5}, {"color", {1, 0.5, 0.25}}}}),
                           json::array({parent, child}));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const auto lights = modelLights(*model);
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].type, LightType::Sun);
  EXPECT_LT(glm::distance(lights[0].direction, glm::dvec3(0.0, 1.0, 0.0)), 1e-6);  // toward the light: up
  EXPECT_FLOAT_EQ(lights[0].intensity, 3.5f);  // lux, as it is
  EXPECT_EQ(lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
}

TEST(PunctualLights, APointLightIsPlacedByTheWholeChainAndTheRoot) {
  json child = lightNode(0);
  child["translation"] = {1, 0, 0};
  json parent{{"translation", {0, 2, 0}}, {"rotation", {0.0, 0.7071068, 0.0, 0.7071068}}, {"children", {1}}};
  auto model = lightsModel(json::array({{{"type", "point"}, {"intensity", 20}}}), json::array({parent, child}));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const auto lights = modelLights(*model, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 10.0)));
  ASSERT_EQ(lights.size(), 1u);
  // +90 degrees about y takes +x to -z.
  EXPECT_LT(glm::distance(lights[0].position, glm::dvec3(0.0, 2.0, 9.0)), 1e-6);
}

// Turned -90 degrees about x, the spot shines straight down: its direction toward
// the light is up, and its cones are kept (degrees), without a warning.
TEST(PunctualLights, ASpotLightKeepsItsConesAndShinesAlongItsNodesMinusZ) {
  json node = lightNode(0);
  node["rotation"] = {-0.7071068, 0.0, 0.0, 0.7071068};
  node["translation"] = {1, 3, 0};
  auto model = lightsModel(
      json::array({{{"type", "spot"}, {"name", "torch"}, {"intensity", 40}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}}}),
      json::array({node}), "spot.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->warnings.empty());
  const auto lights = modelLights(*model);
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].type, LightType::Spot);
  EXPECT_TRUE(lights[0].falloff);
  EXPECT_FLOAT_EQ(lights[0].intensity, 40.0f);  // candela, as it is
  EXPECT_LT(glm::distance(lights[0].position, glm::dvec3(1.0, 3.0, 0.0)), 1e-6);
  EXPECT_LT(glm::distance(lights[0].direction, glm::dvec3(0.0, 1.0, 0.0)), 1e-6);
  EXPECT_NEAR(lights[0].innerConeDegrees, 0.25 * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_NEAR(lights[0].outerConeDegrees, 0.5 * 180.0 / 3.14159265358979, 1e-4);
}

// glTF's defaults: inner 0, outer pi/4; pi/2 as a float (a hair above pi/2) is taken.
TEST(PunctualLights, ASpotsDefaultConesAndAFloatsHalfPi) {
  auto model = lightsModel(json::array({{{"type", "spot"}, {"spot", json::object()}},
                                        {{"type", "spot"}, {"spot", {{"outerConeAngle", 1.5707963705062866}}}}}),
                           json::array({lightNode(0), lightNode(1)}));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const auto lights = modelLights(*model);
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights[0].innerConeDegrees, 0.0f);
  EXPECT_NEAR(lights[0].outerConeDegrees, 45.0f, 1e-4);
  EXPECT_NEAR(lights[1].outerConeDegrees, 90.0f, 1e-4);
}

// Cones the extension does not allow: an error naming the file and the light, for
// each way of breaking 0 <= inner <= outer <= pi/2.
TEST(PunctualLights, ASpotsBadConesNameTheFileAndLight) {
  for (const json& cones : {json{{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}, json{{"outerConeAngle", 1.6}},
                            json{{"innerConeAngle", -0.1}}, json{{"outerConeAngle", -0.2}}}) {
    SCOPED_TRACE(cones.dump());
    auto model = lightsModel(json::array({{{"type", "spot"}, {"name", "torch"}, {"spot", cones}}}), json::array({lightNode(0)}),
                             "cone.gltf");
    ASSERT_FALSE(model.ok());
    EXPECT_EQ(model.error().message, "cone.gltf: light 0 (\"torch\"): spot.innerConeAngle and spot.outerConeAngle must be "
                                     "0 <= inner <= outer <= pi/2");
  }
}

TEST(PunctualLights, ALightThatDoesNotExistNamesTheFileAndNode) {
  auto model = lightsModel(json::array({{{"type", "point"}}}), json::array({json::object(), lightNode(4)}), "missing.gltf");
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.error().message, "missing.gltf: node 1: KHR_lights_punctual: light 4 does not exist (1 lights)");
}

TEST(PunctualLights, ANegativeIntensityNamesTheFileAndLight) {
  auto model = lightsModel(json::array({{{"type", "point"}, {"name", "dark"}, {"intensity", -1}}}), json::array({lightNode(0)}),
                           "dark.gltf");
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.error().message, "dark.gltf: light 0 (\"dark\"): intensity must be a finite number >= 0");
}

TEST(PunctualLights, ANodeOutsideTheSceneAddsNoLight) {
  json orphan = lightNode(0);
  orphan["parentless"] = true;  // not listed in the scene (the key itself is ignored)
  // The scene holds node 1 only (an empty scene would count every root).
  auto model = lightsModel(json::array({{{"type", "point"}}}), json::array({orphan, json::object()}));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(modelLights(*model).empty());
}

}  // namespace
}  // namespace engine
