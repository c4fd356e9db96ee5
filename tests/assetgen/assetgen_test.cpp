// The generated robot: the committed assets/models files are exactly what the
// generator writes today, and the file itself holds the promised structure (joints,
// normalised two-joint blends, three seamless looping clips).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "assetgen.h"
#include "gltf_writer.h"
#include "robot_rig.h"

#ifdef ASSETGEN_HAVE_LOADER
#include "asset/gltf_loader.h"
#endif

namespace assetgen {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kModels = fs::path(ENGINE_SOURCE_DIR) / "assets" / "models";
constexpr const char* kBaseName = "character";

std::vector<std::uint8_t> readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The committed character, parsed by hand so that these checks do not depend on
// the engine's loader.
struct GltfFile {
  json doc;
  std::vector<std::uint8_t> bin;

  static GltfFile load() {
    GltfFile file;
    const OutputNames names = outputNames(kBaseName);
    std::ifstream in(kModels / names.gltf);
    file.doc = json::parse(in);
    file.bin = readFile(kModels / names.bin);
    return file;
  }

  // Element `i`, component `c` of a float or unsigned byte accessor, honouring the
  // view's stride.
  float component(int accessorIndex, size_t i, int c) const {
    const json& accessor = doc["accessors"][accessorIndex];
    const json& view = doc["bufferViews"][accessor["bufferView"].get<int>()];
    const int type = accessor["componentType"];
    const size_t size = type == 5126 ? 4 : 1;
    const size_t components = componentCount(accessor["type"]);
    const size_t stride = view.value("byteStride", static_cast<size_t>(components * size));
    const size_t offset = view.value("byteOffset", size_t{0}) +
                          accessor.value("byteOffset", size_t{0}) + i * stride +
                          static_cast<size_t>(c) * size;
    if (type == 5121) return bin.at(offset);
    float value;
    (void)bin.at(offset + sizeof value - 1);  // throws when the float runs past the end
    std::memcpy(&value, &bin[offset], sizeof value);
    return value;
  }

  static size_t componentCount(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "MAT4") return 16;
    return 4;
  }

  size_t count(int accessorIndex) const { return doc["accessors"][accessorIndex]["count"]; }
};

TEST(AssetgenTest, CommittedFilesMatchTheGenerator) {
  const fs::path out = fs::path(ENGINE_BINARY_DIR) / "test-output" / "assetgen" / "generated";
  fs::remove_all(out);
  const auto written = writeCharacter(buildRobot(), out.string(), kBaseName);
  ASSERT_TRUE(written.ok()) << written.error().message;
  const OutputNames names = outputNames(kBaseName);
  for (const std::string& name : {names.gltf, names.bin, names.image}) {
    const auto fresh = readFile(out / name);
    ASSERT_FALSE(fresh.empty()) << name;
    EXPECT_TRUE(fresh == readFile(kModels / name))
        << "assets/models/" << name << " differs from the generator's output in " << out
        << "; run `build/bin/assetgen` from the project root and commit the result";
  }
}

TEST(AssetgenTest, OutputIsDeterministic) {
  const Character a = buildRobot(), b = buildRobot();
  const GltfFiles fa = toGltf(a, "x.bin", "x.png"), fb = toGltf(b, "x.bin", "x.png");
  EXPECT_EQ(fa.json, fb.json);
  EXPECT_TRUE(fa.bin == fb.bin);
  EXPECT_TRUE(a.albedo.pixels == b.albedo.pixels);
}

TEST(AssetgenTest, SkeletonIsAHumanoid) {
  const GltfFile file = GltfFile::load();
  const json& skin = file.doc["skins"][0];
  const std::vector<std::string> expected = {
      "pelvis",     "spine",  "chest",      "neck",       "head",   "upperarm_l",
      "lowerarm_l", "hand_l", "upperarm_r", "lowerarm_r", "hand_r", "thigh_l",
      "shin_l",     "foot_l", "thigh_r",    "shin_r",     "foot_r"};
  ASSERT_EQ(skin["joints"].size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(file.doc["nodes"][skin["joints"][i].get<int>()]["name"], expected[i]);
  }
  EXPECT_EQ(skin["skeleton"], skin["joints"][0]);
  EXPECT_EQ(file.count(skin["inverseBindMatrices"]), expected.size());

  // The skinned mesh node is a scene root, parented under no joint.
  std::set<int> children;
  for (const json& node : file.doc["nodes"]) {
    for (int child : node.value("children", std::vector<int>{})) children.insert(child);
  }
  const auto& nodes = file.doc["nodes"];
  const auto meshNode =
      std::find_if(nodes.begin(), nodes.end(), [](const json& n) { return n.contains("mesh"); });
  ASSERT_NE(meshNode, nodes.end());
  const int meshIndex = static_cast<int>(std::distance(nodes.begin(), meshNode));
  EXPECT_EQ(children.count(meshIndex), 0u);
  EXPECT_EQ((*meshNode)["skin"], 0);
}

TEST(AssetgenTest, WeightsAreNormalisedWithRealBlends) {
  const GltfFile file = GltfFile::load();
  const json& attributes = file.doc["meshes"][0]["primitives"][0]["attributes"];
  for (const char* name : {"POSITION", "NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"}) {
    ASSERT_TRUE(attributes.contains(name)) << name;
  }
  const int joints = attributes["JOINTS_0"], weights = attributes["WEIGHTS_0"];
  const size_t vertices = file.count(weights);
  ASSERT_GT(vertices, 1000u);
  ASSERT_LT(vertices, 65536u);  // 16-bit indices
  std::set<std::pair<int, int>> blends;
  for (size_t v = 0; v < vertices; ++v) {
    double sum = 0.0;
    std::vector<int> used;
    for (int c = 0; c < 4; ++c) {
      const float w = file.component(weights, v, c);
      const int j = static_cast<int>(file.component(joints, v, c));
      ASSERT_GE(w, 0.0f);
      ASSERT_LT(j, kJointCount);
      sum += w;
      if (w > 0.0f) used.push_back(j);
    }
    ASSERT_NEAR(sum, 1.0, 1e-6) << "vertex " << v;
    ASSERT_LE(used.size(), 2u);
    if (used.size() == 2) blends.insert({std::min(used[0], used[1]), std::max(used[0], used[1])});
  }
  // Elbows, knees and the neck bend smoothly because two joints share their vertices.
  for (auto pair : {std::pair<int, int>{kUpperArmL, kLowerArmL},
                    {kUpperArmR, kLowerArmR},
                    {kThighL, kShinL},
                    {kThighR, kShinR},
                    {kPelvis, kSpine},
                    {kChest, kNeck}}) {
    EXPECT_EQ(blends.count(pair), 1u)
        << "no blend between joints " << pair.first << " and " << pair.second;
  }
}

TEST(AssetgenTest, MaterialIsTexturedAndNotMetal) {
  const GltfFile file = GltfFile::load();
  const json& pbr = file.doc["materials"][0]["pbrMetallicRoughness"];
  EXPECT_EQ(pbr["metallicFactor"].get<float>(), 0.0f);
  EXPECT_NEAR(pbr["roughnessFactor"].get<float>(), 0.6f, 1e-6);
  const int texture = pbr["baseColorTexture"]["index"];
  const int image = file.doc["textures"][texture]["source"];
  const std::string uri = file.doc["images"][image]["uri"];
  EXPECT_TRUE(fs::is_regular_file(kModels / uri)) << uri;
  EXPECT_TRUE(fs::is_regular_file(kModels / file.doc["buffers"][0]["uri"].get<std::string>()));
}

// Duration per clip name, and every loop ends on exactly the key it starts with.
TEST(AssetgenTest, ClipsLoopSeamlessly) {
  const GltfFile file = GltfFile::load();
  const std::vector<std::pair<std::string, float>> expected = {
      {"Idle", 2.0f}, {"Walk", 1.0f}, {"Wave", 1.5f}};
  const json& animations = file.doc["animations"];
  ASSERT_EQ(animations.size(), expected.size());
  std::set<std::string> interpolations;
  for (size_t a = 0; a < expected.size(); ++a) {
    const json& clip = animations[a];
    EXPECT_EQ(clip["name"], expected[a].first);
    ASSERT_FALSE(clip["channels"].empty()) << expected[a].first;
    float duration = 0.0f;
    for (const json& channel : clip["channels"]) {
      const json& sampler = clip["samplers"][channel["sampler"].get<int>()];
      const int input = sampler["input"], output = sampler["output"];
      const std::string interpolation = sampler.value("interpolation", "LINEAR");
      interpolations.insert(interpolation);
      const size_t keys = file.count(input);
      ASSERT_GE(keys, 2u);
      EXPECT_EQ(file.component(input, 0, 0), 0.0f);
      duration = std::max(duration, file.component(input, keys - 1, 0));
      const bool cubic = interpolation == "CUBICSPLINE";
      const size_t perKey = cubic ? 3 : 1;
      ASSERT_EQ(file.count(output), keys * perKey);
      const int components = channel["target"]["path"] == "rotation" ? 4 : 3;
      const std::string what = expected[a].first + " node " + channel["target"]["node"].dump() +
                               " " + channel["target"]["path"].get<std::string>();
      for (size_t k = 0; k < perKey; ++k) {
        for (int c = 0; c < components; ++c) {
          EXPECT_EQ(file.component(output, k, c),
                    file.component(output, (keys - 1) * perKey + k, c))
              << what << " does not loop";
        }
      }
      if (components == 4) {
        for (size_t k = 0; k < keys; ++k) {
          double length2 = 0.0;
          for (int c = 0; c < 4; ++c) length2 += std::pow(file.component(output, k, c), 2.0);
          EXPECT_NEAR(std::sqrt(length2), 1.0, 1e-6) << what << " key " << k;
        }
      }
    }
    EXPECT_FLOAT_EQ(duration, expected[a].second) << expected[a].first;
  }
  EXPECT_EQ(interpolations, (std::set<std::string>{"LINEAR", "STEP", "CUBICSPLINE"}));
}

// The walk moves the pelvis, both legs and both arms.
TEST(AssetgenTest, WalkSwingsLegsAndArms) {
  const GltfFile file = GltfFile::load();
  const json& walk = file.doc["animations"][1];
  std::set<std::pair<int, std::string>> targets;
  for (const json& channel : walk["channels"]) {
    targets.emplace(channel["target"]["node"].get<int>(),
                    channel["target"]["path"].get<std::string>());
  }
  EXPECT_EQ(targets.count({kPelvis, "translation"}), 1u);
  for (int joint : {kThighL, kShinL, kThighR, kShinR, kUpperArmL, kUpperArmR}) {
    EXPECT_EQ(targets.count({joint, "rotation"}), 1u) << "joint " << joint;
  }
}

#ifdef ASSETGEN_HAVE_LOADER
TEST(AssetgenTest, EngineLoaderReadsTheCharacter) {
  const auto model = engine::loadGltf((kModels / outputNames(kBaseName).gltf).string());
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->warnings.empty());
  ASSERT_EQ(model->skins.size(), 1u);
  EXPECT_EQ(model->skins[0].joints.size(), static_cast<size_t>(kJointCount));
  ASSERT_EQ(model->animations.size(), 3u);
  EXPECT_EQ(model->animations[0].name, "Idle");
  EXPECT_FLOAT_EQ(model->animations[1].duration, 1.0f);
  ASSERT_EQ(model->images.size(), 1u);
  EXPECT_FALSE(model->images[0].missing);
  EXPECT_EQ(model->images[0].image.width, kAtlasSize);
}

// The material test model through the engine's loader: every feature it exists
// to show is there, with tangents orthogonal to the normals.
TEST(AssetgenTest, EngineLoaderReadsTheMaterialModel) {
  const auto model = engine::loadGltf((kModels / "materials.gltf").string());
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << model->warnings.front();
  for (const engine::ImageData& image : model->images) EXPECT_FALSE(image.missing) << image.uri;
  auto material = [&](const std::string& name) -> const engine::MaterialData& {
    for (const auto& m : model->materials)
      if (m.name == name) return m;
    ADD_FAILURE() << "no material " << name;
    return model->materials.front();
  };
  const auto& bricks = material("bricks");
  EXPECT_GE(bricks.normalImage, 0);
  EXPECT_GE(bricks.metallicRoughnessImage, 0);
  EXPECT_EQ(bricks.occlusionImage, bricks.metallicRoughnessImage);  // one ORM image
  EXPECT_GE(material("tiles").normalImage, 0);
  EXPECT_GE(material("emissive_panel").emissiveImage, 0);
  EXPECT_EQ(material("leaves").alphaMode, engine::AlphaMode::Mask);
  EXPECT_TRUE(material("leaves").doubleSided);
  EXPECT_EQ(material("glass_blue").alphaMode, engine::AlphaMode::Blend);
  EXPECT_EQ(material("glass_amber").alphaMode, engine::AlphaMode::Blend);
  EXPECT_TRUE(material("two_sided").doubleSided);
  EXPECT_FALSE(material("one_sided").doubleSided);
  for (const auto& mesh : model->meshes) {
    if (mesh.name != "brick_wall" && mesh.name != "tiled_sphere") continue;
    const auto& prim = mesh.primitives[0];
    ASSERT_EQ(prim.tangents.size(), prim.positions.size()) << mesh.name;
    for (size_t v = 0; v < prim.tangents.size(); ++v)
      EXPECT_NEAR(glm::dot(glm::vec3(prim.tangents[v]), prim.normals[v]), 0.0f, 1e-5f) << mesh.name << " " << v;
  }
}
#endif

TEST(AssetgenTest, CommittedMaterialModelMatchesTheGenerator) {
  const fs::path out = fs::path(ENGINE_BINARY_DIR) / "test-output" / "assetgen" / "generated_materials";
  fs::remove_all(out);
  const auto written = writeMaterialsModel(out.string(), "materials");
  ASSERT_TRUE(written.ok()) << written.error().message;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(readFile(entry.path()) == readFile(kModels / name))
        << "assets/models/" << name << " differs from the generator's output in " << out
        << "; run `build/bin/assetgen` from the project root and commit the result";
    ++files;
  }
  EXPECT_EQ(files, 10);  // .gltf, .bin and 8 images
}

}  // namespace
}  // namespace assetgen
