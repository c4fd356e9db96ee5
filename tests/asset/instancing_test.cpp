// EXT_mesh_gpu_instancing: the SimpleInstancing sample (../shared/gltf-samples) has
// 125 instances of one unit cube on its only node, each the TRS of the extension's
// accessors, read here straight from the GLB's bytes to compare with the loader; the
// pose dump writes one mesh entry per instance; attributes of the wrong type or
// count are errors naming the file, the node and the attribute.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "../support/files.h"

namespace engine {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kSample =
    std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/SimpleInstancing/glTF-Binary/SimpleInstancing.glb";

std::uint32_t u32(const std::vector<unsigned char>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// A GLB split into its JSON and BIN chunks, and put back together.
struct Glb {
  json doc;
  std::vector<unsigned char> bin;
  explicit Glb(const std::vector<unsigned char>& b) {
    const std::uint32_t jsonLength = u32(b, 12);
    doc = json::parse(b.begin() + 20, b.begin() + 20 + jsonLength);
    const std::size_t binAt = 20 + jsonLength;
    bin.assign(b.begin() + std::ptrdiff_t(binAt + 8), b.begin() + std::ptrdiff_t(binAt + 8 + u32(b, binAt)));
  }
  std::vector<unsigned char> bytes() const {
    std::string text = doc.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    std::vector<unsigned char> out(28 + text.size() + bin.size());
    auto put = [&](std::size_t at, std::uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
    put(0, 0x46546C67);
    put(4, 2);
    put(8, std::uint32_t(out.size()));
    put(12, std::uint32_t(text.size()));
    put(16, 0x4E4F534A);
    std::memcpy(out.data() + 20, text.data(), text.size());
    put(20 + text.size(), std::uint32_t(bin.size()));
    put(24 + text.size(), 0x004E4942);
    std::memcpy(out.data() + 28 + text.size(), bin.data(), bin.size());
    return out;
  }
  // Element `i` of a tightly packed float accessor, as `n` floats.
  std::vector<float> floats(int accessor, std::size_t i, int n) const {
    const json& a = doc["accessors"][std::size_t(accessor)];
    const json& v = doc["bufferViews"][a["bufferView"].get<std::size_t>()];
    EXPECT_EQ(a["componentType"], 5126);
    EXPECT_FALSE(v.contains("byteStride") && v["byteStride"] != 4 * n);
    const std::size_t at = v.value("byteOffset", std::size_t(0)) + a.value("byteOffset", std::size_t(0)) + i * 4 * std::size_t(n);
    std::vector<float> out(static_cast<std::size_t>(n));
    std::memcpy(out.data(), bin.data() + at, 4 * std::size_t(n));
    return out;
  }
};

class SimpleInstancing : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kSample)) GTEST_SKIP() << kSample << " not found (../shared/gltf-samples absent)";
  }
};

TEST_F(SimpleInstancing, HasTheReadmes125InstancesWithTheirTransforms) {
  auto model = loadGltf(kSample);
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->nodes.size(), 1u);
  const NodeData& node = model->nodes[0];
  ASSERT_EQ(node.instances.size(), 125u);  // README: "causes 125 instances to be rendered"
  for (const std::string& w : model->warnings) ADD_FAILURE() << "warning: " << w;

  const Glb glb(test::readBytes(kSample));
  const json& attributes = glb.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  std::set<std::tuple<float, float, float>> grid;
  for (std::size_t i = 0; i < 125; ++i) {
    SCOPED_TRACE("instance " + std::to_string(i));
    const auto t = glb.floats(attributes["TRANSLATION"].get<int>(), i, 3);
    const auto r = glb.floats(attributes["ROTATION"].get<int>(), i, 4);
    const auto s = glb.floats(attributes["SCALE"].get<int>(), i, 3);
    const glm::mat4 expected = glm::translate(glm::mat4(1.0f), glm::vec3(t[0], t[1], t[2])) *
                               glm::mat4_cast(glm::normalize(glm::quat(r[3], r[0], r[1], r[2]))) *
                               glm::scale(glm::mat4(1.0f), glm::vec3(s[0], s[1], s[2]));
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(node.instances[i][c][k], expected[c][k], 1e-5) << c << "," << k;
    grid.insert({t[0], t[1], t[2]});
  }
  // README: a 5 x 5 x 5 cube from 0 to 10 along each axis; the first instance the
  // plain unit cube, the last at (10, 10, 10) scaled by 2.
  EXPECT_EQ(grid.size(), 125u);
  EXPECT_EQ(node.instances.front(), glm::mat4(1.0f));
  const glm::mat4& last = node.instances.back();
  EXPECT_NEAR(glm::distance(glm::vec3(last[3]), glm::vec3(10.0f)), 0.0f, 1e-5);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::length(glm::vec3(last[c])), 2.0f, 1e-5);
}

TEST_F(SimpleInstancing, PoseDumpWritesEachInstanceAsAMesh) {
  auto model = loadGltf(kSample);
  ASSERT_TRUE(model.ok()) << model.error().message;
  auto pose = dumpPose(*model, -1, 0.0);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  const json& meshes = (*pose)["meshes"];
  ASSERT_EQ(meshes.size(), 125u);
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    EXPECT_EQ(meshes[i]["instance"], i);
    // The first position of the cube, moved by the instance.
    const glm::vec3 p0 = model->meshes[0].primitives[0].positions[0];
    const glm::vec3 expected = glm::vec3(model->nodes[0].instances[i] * glm::vec4(p0, 1.0f));
    const glm::vec3 got(meshes[i]["positions"][0].get<float>(), meshes[i]["positions"][1].get<float>(),
                        meshes[i]["positions"][2].get<float>());
    EXPECT_LT(glm::distance(got, expected), 1e-5f) << i;
  }
}

// The sample with one edit to its JSON, loaded from memory as `name`.
Result<ModelData> edited(const std::string& name, const std::function<void(json&)>& edit) {
  Glb glb(test::readBytes(kSample));
  edit(glb.doc);
  const auto bytes = glb.bytes();
  return loadGltfFromMemory(bytes, name);
}

json& instancingAttributes(json& doc) { return doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]; }

TEST_F(SimpleInstancing, AnAttributeOfTheWrongTypeNamesFileNodeAndAttribute) {
  auto model = edited("rotation_vec3.glb", [](json& doc) { instancingAttributes(doc)["ROTATION"] = 3; });
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.error().message,
            "rotation_vec3.glb: node 0: EXT_mesh_gpu_instancing ROTATION: accessor 3 has 3 components per element, "
            "expected 4 (VEC4)");
}

TEST_F(SimpleInstancing, AttributesOfDifferentCountsNameFileNodeAndAttribute) {
  auto model = edited("scale_count.glb", [](json& doc) {
    doc["accessors"][instancingAttributes(doc)["SCALE"].get<std::size_t>()]["count"] = 124;
  });
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.error().message, "scale_count.glb: node 0: EXT_mesh_gpu_instancing SCALE: has 124 instances, the other attributes 125");
}

TEST_F(SimpleInstancing, AnAttributeThatIsNotAnAccessorIsAnError) {
  auto model = edited("missing.glb", [](json& doc) { instancingAttributes(doc)["TRANSLATION"] = 99; });
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("missing.glb: node 0: EXT_mesh_gpu_instancing TRANSLATION"), std::string::npos)
      << model.error().message;
}

TEST_F(SimpleInstancing, OnlyTranslationLeavesRotationAndScaleAlone) {
  auto model = edited("translation_only.glb", [](json& doc) {
    instancingAttributes(doc).erase("ROTATION");
    instancingAttributes(doc).erase("SCALE");
  });
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->nodes[0].instances.size(), 125u);
  const glm::mat4& last = model->nodes[0].instances.back();
  EXPECT_EQ(glm::mat3(last), glm::mat3(1.0f));
  EXPECT_EQ(glm::vec3(last[3]), glm::vec3(10.0f));
}

// glTF places a skinned mesh by its joints: the instances are dropped with a
// warning, and the mesh is drawn once, skinned.
TEST_F(SimpleInstancing, ASkinnedNodeIsDrawnOnceWithAWarning) {
  auto model = edited("skinned.glb", [](json& doc) {
    doc["nodes"].push_back(json{{"name", "joint"}});
    doc["scenes"][0]["nodes"].push_back(1);
    doc["skins"] = json::array({json{{"joints", json::array({1})}}});
    doc["nodes"][0]["skin"] = 0;
  });
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->nodes[0].instances.empty());
  ASSERT_FALSE(model->warnings.empty());
  EXPECT_NE(model->warnings.back().find("skinned.glb: node 0: EXT_mesh_gpu_instancing: the node is skinned"),
            std::string::npos)
      << model->warnings.back();
}

}  // namespace
}  // namespace engine
