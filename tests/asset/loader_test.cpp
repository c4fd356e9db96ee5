// loadGltf on a small skinned model written by the test itself, then on broken
// variants of it: each must fail with a message that names the element.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "anim/model_builder.h"
#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "asset/material_variants.h"
#include "asset/texture_transform.h"

namespace engine {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Buffer layout of the test model (byte offsets):
//   0 positions 3 x vec3 | 36 joints 3 x u8vec4 | 48 weights 3 x vec4
//   96 indices 3 x u16 (+2 pad) | 104 inverse binds 2 x mat4
//   232 key times 2 x f32 | 240 rotation keys 2 x vec4   (272 bytes)
struct TestModel {
  json doc;
  std::vector<unsigned char> bin = std::vector<unsigned char>(272, 0);

  TestModel() {

    float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    put(0, positions, sizeof positions);
    unsigned char joints[12] = {0, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0};
    put(36, joints, sizeof joints);
    // Sums 0.75, 1 and 2: the loader must normalise them.
    float weights[12] = {0.5f, 0.25f, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0};
    put(48, weights, sizeof weights);
    std::uint16_t indices[3] = {0, 1, 2};
    put(96, indices, sizeof indices);
    float ibm[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    put(104, ibm, sizeof ibm);
    float times[2] = {0.0f, 1.0f};
    put(232, times, sizeof times);
    float rotations[8] = {0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f};
    put(240, rotations, sizeof rotations);

    auto view = [](int offset, int length) { return json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}}; };
    auto accessor = [](int viewIndex, int componentType, int count, const char* type) {
      return json{{"bufferView", viewIndex}, {"componentType", componentType}, {"count", count}, {"type", type}};
    };
    doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"nodes",
         {{{"mesh", 0}, {"skin", 0}, {"name", "body"}},
          {{"children", {2}}, {"name", "hip"}},
          {{"translation", {0, 1, 0}}, {"name", "spine"}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}}, {"indices", 3}}}}}}},
        {"skins", {{{"joints", {1, 2}}, {"inverseBindMatrices", 4}}}},
        {"animations",
         {{{"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}}},
           {"samplers", {{{"input", 5}, {"output", 6}, {"interpolation", "LINEAR"}}}}}}},
        {"buffers", {{{"byteLength", 272}, {"uri", "model.bin"}}}},
        {"bufferViews", {view(0, 36), view(36, 12), view(48, 48), view(96, 6), view(104, 128), view(232, 8), view(240, 32)}},
        {"accessors",
         {accessor(0, 5126, 3, "VEC3"), accessor(1, 5121, 3, "VEC4"), accessor(2, 5126, 3, "VEC4"),
          accessor(3, 5123, 3, "SCALAR"), accessor(4, 5126, 2, "MAT4"), accessor(5, 5126, 2, "SCALAR"),
          accessor(6, 5126, 2, "VEC4")}},
    };
    doc["accessors"][0]["min"] = {0, 0, 0};
    doc["accessors"][0]["max"] = {1, 1, 0};
    doc["accessors"][5]["min"] = {0};
    doc["accessors"][5]["max"] = {1};
  }

  void put(std::size_t offset, const void* data, std::size_t size) { std::memcpy(bin.data() + offset, data, size); }
  void putFloat(std::size_t offset, float v) { put(offset, &v, 4); }

  std::vector<unsigned char> glb() const {
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::uint32_t header[5] = {0x46546C67, 2, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()),
                               static_cast<std::uint32_t>(text.size()), 0x4E4F534A};
    std::uint32_t binHeader[2] = {static_cast<std::uint32_t>(bin.size()), 0x004E4942};
    // Sized up front and filled with memcpy: GCC 12 warns falsely on vector::insert here.
    std::vector<unsigned char> out(sizeof header + text.size() + sizeof binHeader + bin.size());
    unsigned char* p = out.data();
    std::memcpy(p, header, sizeof header);
    p += sizeof header;
    std::memcpy(p, text.data(), text.size());
    p += text.size();
    std::memcpy(p, binHeader, sizeof binHeader);
    p += sizeof binHeader;
    std::memcpy(p, bin.data(), bin.size());
    return out;
  }
};

class LoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("engine_loader_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                        "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "models");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const TestModel& m, const std::string& name = "model.gltf") {
    writeBytes(dir_ / "models" / "model.bin", m.bin);
    std::ofstream(dir_ / "models" / name) << m.doc.dump(1);
    return (dir_ / "models" / name).string();
  }
  void writeBytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  // Each (extension, key, value) set on material 0 of `m` is refused with a message
  // naming the material, the extension and the key.
  void expectMaterialValuesRefused(const TestModel& m,
                                   const std::vector<std::tuple<const char*, const char*, nlohmann::json>>& bad) {
    for (const auto& [extension, key, value] : bad) {
      TestModel broken = m;
      broken.doc["materials"][0]["extensions"][extension][key] = value;
      auto refused = loadGltf(write(broken));
      ASSERT_FALSE(refused.ok()) << extension << " " << key << " " << value.dump();
      EXPECT_NE(refused.error().message.find(std::string("material 0") + ": " + extension + ": " + key),
                std::string::npos)
          << refused.error().message;
    }
  }
  // Loads and expects failure whose message contains every needle.
  void expectError(const std::string& path, std::initializer_list<std::string> needles) {
    auto model = loadGltf(path);
    ASSERT_FALSE(model.ok()) << "loaded although broken: " << path;
    const std::string& message = model.error().message;
    EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos) << message;
    for (const std::string& needle : needles) EXPECT_NE(message.find(needle), std::string::npos) << message;
  }

  fs::path dir_;
};

TEST_F(LoaderTest, LoadsTheValidModel) {
  TestModel m;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->nodes.size(), 3u);
  EXPECT_EQ(model->nodes[2].parent, 1);
  EXPECT_EQ(model->sceneRoots, (std::vector<int>{0, 1}));
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  EXPECT_EQ(prim.influences, 4);
  EXPECT_EQ(prim.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_NEAR(prim.weights[0], 2.0f / 3.0f, 1e-6f);  // 0.5 / 0.75
  EXPECT_NEAR(prim.weights[1], 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(prim.weights[8], 0.5f, 1e-6f);  // 1 / 2
  EXPECT_EQ(model->skins[0].inverseBinds[1][3][1], -1.0f);
  ASSERT_EQ(model->animations.size(), 1u);
  EXPECT_EQ(model->animations[0].duration, 1.0f);
  EXPECT_EQ(model->animations[0].channels[0].path, AnimPath::Rotation);
}

TEST_F(LoaderTest, LoadsTheSameModelAsGlb) {
  TestModel m;
  m.doc["buffers"][0].erase("uri");
  writeBytes(dir_ / "models" / "model.glb", m.glb());
  auto model = loadGltf((dir_ / "models" / "model.glb").string());
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->meshes[0].primitives[0].positions[1], glm::vec3(1, 0, 0));
}

TEST_F(LoaderTest, PoseDumpSkinsWithTheWorldOfTheJoints) {
  TestModel m;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok());
  // At t = 1 the spine (joint at (0,1,0)) is rotated 90 degrees about z.
  // Vertex 1 (1,0,0) follows the spine only: (1,-1) from the joint turns to
  // (1,1), so it lands at (1,2,0). Vertex 0 (origin) is 2/3 hip (unmoved) and
  // 1/3 spine (which takes it to (1,1,0)): (1/3, 1/3, 0).
  auto pose = dumpPose(*model, 0, 1.0, LoopMode::Clamp);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  const json& positions = (*pose)["meshes"][0]["positions"];
  EXPECT_NEAR(positions[3].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(positions[4].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(positions[0].get<double>(), 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(positions[1].get<double>(), 1.0 / 3.0, 1e-6);
  EXPECT_EQ((*pose)["nodes"].size(), 3u);
  EXPECT_EQ((*pose)["nodes"][2]["world"].size(), 16u);
  EXPECT_FALSE(dumpPose(*model, 3, 0.0).ok());
}

TEST_F(LoaderTest, ReadsSparseAndNormalisedAccessors) {
  TestModel m;
  // Sparse: one substitution, index 0 (the first u16 of the index data) with the
  // value (0, 1, 0) (floats 2..4 of the rotation keys).
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 2}});   // index: u16 0
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 248}, {"byteLength", 12}}); // values (0, 1, 0)
  m.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", 7}, {"componentType", 5123}}},
                                     {"values", {{"bufferView", 8}}}};
  // Weights as normalised unsigned bytes read from the joints bytes.
  m.doc["accessors"][2] = {{"bufferView", 1}, {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC4"}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  EXPECT_EQ(prim.positions[0], glm::vec3(0, 1, 0));
  EXPECT_EQ(prim.positions[1], glm::vec3(1, 0, 0));
  EXPECT_NEAR(prim.weights[4 * 2 + 0], 0.5f, 1e-6f);  // bytes (1, 1, 0, 0) / 255, normalised
}

// COLOR_0 (the base colour's multiplier): VEC4 of normalised unsigned bytes and VEC3
// of floats (alpha 1); any other type or count names the primitive and attribute.
TEST_F(LoaderTest, ReadsVertexColours) {
  TestModel m;
  m.doc["accessors"].push_back({{"bufferView", 1}, {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC4"}});
  m.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 7;  // the joints' bytes
  auto bytes = loadGltf(write(m));
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const std::vector<glm::vec4>& c = bytes->meshes[0].primitives[0].colors;
  ASSERT_EQ(c.size(), 3u);
  const float one = float(1.0 / 255.0);  // as readAccessor divides, in double
  EXPECT_EQ(c[0], glm::vec4(0.0f, one, 0.0f, 0.0f));
  EXPECT_EQ(c[2], glm::vec4(one, one, 0.0f, 0.0f));

  m.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 0;  // the positions, VEC3 floats
  auto floats = loadGltf(write(m));
  ASSERT_TRUE(floats.ok()) << floats.error().message;
  EXPECT_EQ(floats->meshes[0].primitives[0].colors[1], glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));

  m.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 3;  // the indices: SCALAR
  expectError(write(m), {"mesh 0 primitive 0 COLOR_0", "must be VEC3 or VEC4"});
  m.doc["accessors"][7]["count"] = 2;
  m.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 7;
  expectError(write(m), {"COLOR_0", "has 2 elements, expected 3"});
}

TEST_F(LoaderTest, InterleavedByteStride) {
  TestModel m;
  // Read POSITION x,y,z with a 12-byte stride explicitly, and weights with 16.
  m.doc["bufferViews"][0]["byteStride"] = 12;
  m.doc["bufferViews"][2]["byteStride"] = 16;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  m.doc["bufferViews"][0]["byteStride"] = 8;  // smaller than a vec3
  expectError(write(m), {"bufferView 0", "byteStride"});
}

TEST_F(LoaderTest, TruncatedGlb) {
  TestModel m;
  m.doc["buffers"][0].erase("uri");
  auto bytes = m.glb();
  bytes.resize(bytes.size() - 40);
  writeBytes(dir_ / "models" / "cut.glb", bytes);
  expectError((dir_ / "models" / "cut.glb").string(), {"truncated"});
  bytes.resize(10);
  writeBytes(dir_ / "models" / "cut.glb", bytes);
  expectError((dir_ / "models" / "cut.glb").string(), {"truncated"});
}

TEST_F(LoaderTest, AccessorPastItsBufferView) {
  TestModel m;
  m.doc["accessors"][0]["count"] = 4;
  expectError(write(m), {"accessor 0", "bufferView 0"});
  TestModel n;
  n.doc["accessors"][5]["byteOffset"] = 8;
  expectError(write(n), {"accessor 5"});
}

TEST_F(LoaderTest, BufferViewPastItsBuffer) {
  TestModel m;
  m.doc["bufferViews"][6]["byteLength"] = 4000;
  expectError(write(m), {"bufferView 6"});
}

TEST_F(LoaderTest, SkinJointWithoutNode) {
  TestModel m;
  m.doc["skins"][0]["joints"] = {1, 9};
  expectError(write(m), {"skin 0", "joint 1"});
}

TEST_F(LoaderTest, VertexJointPastTheSkin) {
  TestModel m;
  unsigned char j = 5;
  m.put(36 + 4, &j, 1);  // vertex 1's first joint
  expectError(write(m), {"vertex 1", "joint 5", "skin 0"});
}

TEST_F(LoaderTest, BadKeyTimes) {
  TestModel nan;
  nan.putFloat(236, std::numeric_limits<float>::quiet_NaN());
  nan.doc["accessors"][5].erase("max");
  expectError(write(nan), {"animation 0", "key 1", "NaN"});
  TestModel negative;
  negative.putFloat(232, -0.5f);
  negative.doc["accessors"][5]["min"] = {-0.5};
  expectError(write(negative), {"animation 0", "key 0", "negative"});
  TestModel unsorted;
  unsorted.putFloat(232, 2.0f);
  unsorted.doc["accessors"][5]["min"] = {1};
  unsorted.doc["accessors"][5]["max"] = {2};
  expectError(write(unsorted), {"animation 0", "key 1", "sorted"});
}

TEST_F(LoaderTest, NaNKeyValue) {
  TestModel m;
  m.putFloat(244, std::numeric_limits<float>::quiet_NaN());
  expectError(write(m), {"animation 0", "output", "element 0"});
}

TEST_F(LoaderTest, CyclesAndTwoParents) {
  TestModel cycle;
  cycle.doc["nodes"][2]["children"] = {1};
  cycle.doc["scenes"][0]["nodes"] = {0};
  expectError(write(cycle), {"cycle"});
  TestModel self;
  self.doc["nodes"][1]["children"] = {1};
  expectError(write(self), {"node 1", "cycle"});
  TestModel twoParents;
  twoParents.doc["nodes"][0]["children"] = {2};
  expectError(write(twoParents), {"node 2", "two parents"});
}

TEST_F(LoaderTest, UrisThatLeaveTheFolderAreRefused) {
  for (const char* uri : {"../model.bin", "/etc/passwd", "sub/../../x.bin", "%2e%2e/model.bin", "file:///etc/passwd"}) {
    TestModel m;
    m.doc["buffers"][0]["uri"] = uri;
    expectError(write(m), {"buffer 0", "leaves the model's folder"});
  }
  TestModel image;
  image.doc["images"] = {{{"uri", "../secret.png"}}};
  expectError(write(image), {"image 0", "leaves"});
}

TEST_F(LoaderTest, MissingBufferIsAnError) {
  TestModel m;
  m.doc["buffers"][0]["uri"] = "nothere.bin";
  expectError(write(m), {"nothere.bin"});
}

TEST_F(LoaderTest, MissingTextureWarnsAndFallsBack) {
  TestModel m;
  m.doc["images"] = {{{"uri", "missing.png"}}};
  m.doc["textures"] = {{{"source", 0}}};
  m.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  m.doc["meshes"][0]["primitives"][0]["material"] = 0;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->images.size(), 1u);
  EXPECT_TRUE(model->images[0].missing);
  EXPECT_EQ(model->images[0].image.width, 1);
  EXPECT_EQ(model->materials[0].baseColorImage, 0);
  EXPECT_FALSE(model->warnings.empty());
}

TEST_F(LoaderTest, HugeImageIsRefusedBeforeDecoding) {
  // A PNG header claiming 60000 x 60000 pixels (14 GB decoded), nothing more.
  std::vector<unsigned char> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                 0, 0, 0xEA, 0x60, 0, 0, 0xEA, 0x60, 8, 6, 0, 0, 0};
  writeBytes(dir_ / "models" / "huge.png", png);
  TestModel m;
  m.doc["images"] = {{{"uri", "huge.png"}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->images[0].missing);
}

// Every truncation and a few thousand corrupted bytes of a GLB: any outcome but a
// crash (or a sanitizer report) is acceptable.
TEST_F(LoaderTest, SurvivesTruncatedAndCorruptedGlb) {
  TestModel m;
  m.doc["buffers"][0].erase("uri");
  const std::vector<unsigned char> good = m.glb();
  fs::path path = dir_ / "models" / "fuzz.glb";
  for (std::size_t length = 0; length < good.size(); length += 5) {
    writeBytes(path, std::vector<unsigned char>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(length)));
    EXPECT_FALSE(loadGltf(path.string()).ok()) << length;
  }
  std::uint32_t state = 12345;
  auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  for (int round = 0; round < 400; ++round) {
    std::vector<unsigned char> bytes = good;
    for (int k = 0; k < 3; ++k) bytes[next() % bytes.size()] = static_cast<unsigned char>(next() >> 24);
    writeBytes(path, bytes);
    auto model = loadGltf(path.string());
    if (model.ok()) (void)dumpPose(*model, model->animations.empty() ? -1 : 0, 0.5);
  }
}

TEST_F(LoaderTest, TooManyJoints) {
  TestModel m;
  m.doc["skins"][0]["joints"] = json(std::vector<int>(kMaxSkinJoints + 1, 1));
  expectError(write(m), {"skin 0", "limit"});
}

TEST_F(LoaderTest, MissingFileAndBadJson) {
  expectError((dir_ / "models" / "nope.gltf").string(), {"cannot open"});
  std::ofstream(dir_ / "models" / "bad.gltf") << "{ not json";
  expectError((dir_ / "models" / "bad.gltf").string(), {"JSON"});
}

TEST_F(LoaderTest, MatrixNodesAreDecomposed) {
  TestModel m;
  m.doc["nodes"][2].erase("translation");
  m.doc["nodes"][2]["matrix"] = {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const NodeData& n = model->nodes[2];
  EXPECT_LT(glm::distance(n.scale, glm::vec3(2)), 1e-6f);
  EXPECT_LT(glm::distance(n.translation, glm::vec3(1, 2, 3)), 1e-6f);
  EXPECT_NEAR(glm::angle(n.rotation), 1.5707963f, 1e-5f);
}

}  // namespace
}  // namespace engine


namespace engine {
namespace {

// The test model with NORMAL and TEXCOORD_0 (appended to its buffer) and a
// normal-mapped material, for the material checks below.
TestModel normalMappedModel(const std::string& imageUri) {
  TestModel m;
  m.bin.resize(272 + 36 + 24, 0);
  const float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.put(272, normals, sizeof normals);
  const float uvs[6] = {0, 1, 1, 1, 0, 0};
  m.put(308, uvs, sizeof uvs);
  m.doc["buffers"][0]["byteLength"] = m.bin.size();
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 272}, {"byteLength", 36}});
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 308}, {"byteLength", 24}});
  m.doc["accessors"].push_back({{"bufferView", 7}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  m.doc["accessors"].push_back({{"bufferView", 8}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  auto& attributes = m.doc["meshes"][0]["primitives"][0]["attributes"];
  attributes["NORMAL"] = 7;
  attributes["TEXCOORD_0"] = 8;
  m.doc["images"] = {{{"uri", imageUri}}};
  m.doc["textures"] = {{{"source", 0}}};
  m.doc["materials"] = {{{"name", "brick"}, {"normalTexture", {{"index", 0}, {"scale", 0.5}}}}};
  m.doc["meshes"][0]["primitives"][0]["material"] = 0;
  return m;
}

bool hasWarning(const ModelData& model, std::initializer_list<std::string> needles) {
  for (const std::string& w : model.warnings) {
    bool all = true;
    for (const std::string& n : needles) all = all && w.find(n) != std::string::npos;
    if (all) return true;
  }
  return false;
}

std::string allWarnings(const ModelData& model) {
  std::string out;
  for (const std::string& w : model.warnings) out += w + "\n";
  return out;
}

TEST_F(LoaderTest, NormalMapWithoutTangentsGetsGeneratedOnes) {
  TestModel m = normalMappedModel("normal.png");
  Image png(2, 2);
  std::fill(png.pixels.begin(), png.pixels.end(), std::uint8_t{200});
  ASSERT_TRUE(writePng((dir_ / "models" / "normal.png").string(), png).ok());
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialData& material = model->materials[0];
  EXPECT_EQ(material.normalImage, 0);
  EXPECT_FLOAT_EQ(material.normalScale, 0.5f);
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  ASSERT_EQ(prim.tangents.size(), 3u);
  // u runs along +x, v down the image along -y: tangent +x, right-handed.
  for (const glm::vec4& t : prim.tangents) {
    EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(t.w, 1.0f);
  }
}

TEST_F(LoaderTest, MissingNormalMapFallsBackToTheMeshNormals) {
  auto model = loadGltf(write(normalMappedModel("bricks_normal.png")));
  ASSERT_TRUE(model.ok()) << model.error().message;
  // The white fallback would tilt every normal: the map is dropped instead, and
  // the warning names the file, the material and the slot.
  EXPECT_EQ(model->materials[0].normalImage, -1);
  EXPECT_TRUE(hasWarning(*model, {"model.gltf", "material 0 (\"brick\")", "normalTexture", "bricks_normal.png"}))
      << allWarnings(*model);
  EXPECT_TRUE(model->meshes[0].primitives[0].tangents.empty());
}

TEST_F(LoaderTest, MaterialTextureIndexOutOfRangeIsIgnoredWithAWarning) {
  TestModel m = normalMappedModel("normal.png");
  m.doc["materials"][0]["normalTexture"]["index"] = 7;
  m.doc["materials"][0]["occlusionTexture"] = {{"index", 3}};
  m.doc["materials"][0]["pbrMetallicRoughness"] = {{"metallicRoughnessTexture", {{"index", -2}}}};
  m.doc["materials"][0]["emissiveTexture"] = {{"index", 0}, {"texCoord", 1}};
  m.doc["materials"][0]["alphaMode"] = "MASK";
  m.doc["materials"][0]["alphaCutoff"] = 0.25;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialData& material = model->materials[0];
  EXPECT_EQ(material.normalImage, -1);
  EXPECT_EQ(material.occlusionImage, -1);
  EXPECT_EQ(material.metallicRoughnessImage, -1);
  EXPECT_EQ(material.emissiveImage, 0);
  EXPECT_EQ(material.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(material.alphaCutoff, 0.25f);
  EXPECT_TRUE(hasWarning(*model, {"model.gltf", "material 0 (\"brick\")", "normalTexture 7 does not exist"}))
      << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"occlusionTexture 3 does not exist"})) << allWarnings(*model);
  // TEXCOORD_1 is read now; the primitive has none, so the warning names that.
  EXPECT_TRUE(hasWarning(*model, {"model.gltf", "material 0 (\"brick\")", "emissiveTexture", "TEXCOORD_1",
                                  "TEXCOORD_0 is used"}))
      << allWarnings(*model);
}

// normalMappedModel with its uvs also as TEXCOORD_1, a base colour texture that
// reads set 1 through the KHR_texture_transform of the extension's own example
// (offset [0, 1], rotation pi/2, scale 0.5: the lower left quadrant turned 90
// degrees clockwise), and an emissive texture through a sampler.
TestModel transformedModel() {
  TestModel m = normalMappedModel("normal.png");
  m.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 8;
  m.doc["extensionsUsed"] = {"KHR_texture_transform"};
  m.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}, {"minFilter", 9984}}, json::object()};
  m.doc["textures"] = {{{"source", 0}}, {{"source", 0}, {"sampler", 0}}, {{"source", 0}, {"sampler", 1}}};
  m.doc["materials"][0]["pbrMetallicRoughness"] = {
      {"baseColorTexture",
       {{"index", 0},
        {"texCoord", 1},
        {"extensions",
         {{"KHR_texture_transform", {{"offset", {0.0, 1.0}}, {"rotation", 1.57079632679}, {"scale", {0.5, 0.5}}}}}}}},
      {"metallicRoughnessTexture", {{"index", 2}}}};
  m.doc["materials"][0]["emissiveTexture"] = {{"index", 1}};
  return m;
}

TEST_F(LoaderTest, ReadsTexCoordTextureTransformAndSamplers) {
  ASSERT_TRUE(writePng((dir_ / "models" / "normal.png").string(), Image(2, 2)).ok());
  auto model = loadGltf(write(transformedModel()));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  ASSERT_EQ(prim.uvs1.size(), 3u);
  EXPECT_EQ(prim.uvs1[0], glm::vec2(0, 1));
  const MaterialData& material = model->materials[0];
  const TextureSlotData& base = material.texture(TextureSlot::BaseColor);
  EXPECT_EQ(base.texCoord, 1);
  EXPECT_TRUE(base.transformsUv());
  // The example's corners: (0, 0) -> (0, 1), (1, 0) -> (0, 0.5), (0, 1) -> (0.5, 1).
  auto near = [](glm::vec2 a, glm::vec2 b) { return glm::distance(a, b) < 1e-6f; };
  EXPECT_TRUE(near(transformUv(base.uvTransform, {0, 0}), {0, 1}));
  EXPECT_TRUE(near(transformUv(base.uvTransform, {1, 0}), {0, 0.5f}));
  EXPECT_TRUE(near(transformUv(base.uvTransform, {0, 1}), {0.5f, 1}));
  // No sampler: repeat, trilinear.
  EXPECT_EQ(base.sampler, SamplerData{});
  const TextureSlotData& emissive = material.texture(TextureSlot::Emissive);
  EXPECT_EQ(emissive.texCoord, 0);
  EXPECT_FALSE(emissive.transformsUv());
  EXPECT_EQ(emissive.sampler.wrapS, TextureWrap::ClampToEdge);
  EXPECT_EQ(emissive.sampler.wrapT, TextureWrap::MirroredRepeat);
  EXPECT_EQ(emissive.sampler.magFilter, TextureFilter::Nearest);
  EXPECT_EQ(emissive.sampler.minFilter, TextureFilter::NearestMipmapNearest);
  // An empty sampler is glTF's defaults.
  EXPECT_EQ(material.texture(TextureSlot::MetallicRoughness).sampler, SamplerData{});
  // The untouched slots keep theirs.
  EXPECT_EQ(material.texture(TextureSlot::Occlusion).uvTransform, glm::mat3(1.0f));
  EXPECT_EQ(material.texture(TextureSlot::Occlusion).texCoord, 0);
}

// The extension's texCoord overrides the textureInfo's; required, it is supported.
TEST_F(LoaderTest, TextureTransformTexCoordOverridesAndMayBeRequired) {
  ASSERT_TRUE(writePng((dir_ / "models" / "normal.png").string(), Image(2, 2)).ok());
  TestModel m = transformedModel();
  m.doc["extensionsRequired"] = {"KHR_texture_transform"};
  m.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
      {"texCoord", 0}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  const TextureSlotData& base = model->materials[0].texture(TextureSlot::BaseColor);
  EXPECT_EQ(base.texCoord, 0);
  EXPECT_EQ(base.uvTransform, glm::mat3(1.0f));  // no offset, rotation or scale: identity
  EXPECT_FALSE(base.transformsUv());
}

// Bad texture settings warn, naming the file, the material and the slot, and load
// with the defaults: no crash, no refused model.
TEST_F(LoaderTest, BadTexCoordTransformAndSamplerWarnAndUseDefaults) {
  ASSERT_TRUE(writePng((dir_ / "models" / "normal.png").string(), Image(2, 2)).ok());
  TestModel m = transformedModel();
  m.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
  auto& pbr = m.doc["materials"][0]["pbrMetallicRoughness"];
  pbr["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
      {"offset", "far"}, {"rotation", "left"}, {"scale", json::array({2.0})}, {"texCoord", -1}};
  m.doc["materials"][0]["occlusionTexture"] = {{"index", 0}, {"texCoord", 2}};
  m.doc["samplers"][0] = {{"wrapS", 1234}, {"magFilter", 9984}, {"minFilter", 5}};
  m.doc["textures"][2]["sampler"] = 9;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const std::string material = "material 0 (\"brick\")";
  for (const char* needle : {"offset must be 2 finite numbers", "rotation must be a finite number",
                             "scale must be 2 finite numbers", "texCoord must be an integer >= 0"})
    EXPECT_TRUE(hasWarning(*model, {"model.gltf", material, "baseColorTexture 0: KHR_texture_transform", needle}))
        << needle << "\n" << allWarnings(*model);
  // Set 1 (from the textureInfo) on a primitive without TEXCOORD_1: set 0 is read.
  EXPECT_TRUE(hasWarning(*model, {"model.gltf", "mesh 0", material, "baseColorTexture reads TEXCOORD_1",
                                  "TEXCOORD_0 is used"}))
      << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"model.gltf", material, "occlusionTexture 0: TEXCOORD_2 is not supported"}))
      << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"emissiveTexture 1: sampler 0: wrapS 1234 is not a wrap mode"})) << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"sampler 0: magFilter 9984 is not NEAREST or LINEAR"})) << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"sampler 0: minFilter 5"})) << allWarnings(*model);
  EXPECT_TRUE(hasWarning(*model, {"metallicRoughnessTexture 2: sampler 9 does not exist"})) << allWarnings(*model);

  const MaterialData& mat = model->materials[0];
  const TextureSlotData& base = mat.texture(TextureSlot::BaseColor);
  EXPECT_EQ(base.texCoord, 1);
  EXPECT_EQ(base.uvTransform, glm::mat3(1.0f));
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  EXPECT_EQ(prim.uvs1, prim.uvs);
  EXPECT_EQ(mat.texture(TextureSlot::Occlusion).texCoord, 0);
  EXPECT_EQ(mat.texture(TextureSlot::Emissive).sampler.wrapS, TextureWrap::Repeat);
  EXPECT_EQ(mat.texture(TextureSlot::Emissive).sampler.wrapT, TextureWrap::Repeat);  // absent: the default
  EXPECT_EQ(mat.texture(TextureSlot::Emissive).sampler.magFilter, TextureFilter::Linear);
  EXPECT_EQ(mat.texture(TextureSlot::Emissive).sampler.minFilter, TextureFilter::LinearMipmapLinear);
  EXPECT_EQ(mat.texture(TextureSlot::MetallicRoughness).sampler, SamplerData{});
}

// T * R * S against hand-worked values: a rotation alone turns u = (1, 0) to
// (cos r, -sin r), counter-clockwise with v down; the order is scale, rotate,
// then offset.
TEST(TextureTransform, MatrixIsTranslationRotationScale) {
  const float r = 0.3f;
  const glm::mat3 rotate = textureTransformMatrix({0, 0}, r, {1, 1});
  EXPECT_NEAR(glm::distance(transformUv(rotate, {1, 0}), glm::vec2(std::cos(r), -std::sin(r))), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(transformUv(rotate, {0, 1}), glm::vec2(std::sin(r), std::cos(r))), 0.0f, 1e-6f);
  const glm::mat3 all = textureTransformMatrix({-0.2f, -0.1f}, r, {1.5f, 2.0f});
  const glm::vec2 uv(0.4f, 0.7f);
  const glm::vec2 scaled = uv * glm::vec2(1.5f, 2.0f);
  const glm::vec2 expected = glm::vec2(std::cos(r) * scaled.x + std::sin(r) * scaled.y,
                                       -std::sin(r) * scaled.x + std::cos(r) * scaled.y) +
                             glm::vec2(-0.2f, -0.1f);
  EXPECT_NEAR(glm::distance(transformUv(all, uv), expected), 0.0f, 1e-6f);
  EXPECT_EQ(textureTransformMatrix({0, 0}, 0.0f, {1, 1}), glm::mat3(1.0f));
}


// A required extension this engine lacks is an error listing them all, checked
// before tinygltf (which would report what the extension leaves out, such as a
// compressed texture's missing source, instead); an optional one is a warning
// naming it, and the model loads without it. The supported ones, compressions
// included, are neither.
TEST_F(LoaderTest, UnsupportedExtensionsRequiredAreErrorsUsedAreWarnings) {
  TestModel required;
  required.doc["extensionsUsed"] = {"KHR_texture_basisu", "KHR_mesh_quantization", "KHR_draco_mesh_compression",
                                    "EXT_meshopt_compression", "EXT_unheard_of"};
  required.doc["extensionsRequired"] = required.doc["extensionsUsed"];
  required.doc["accessors"][0].erase("bufferView");
  const std::string path = write(required);
  auto refused = loadGltf(path);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            path + ": requires KHR_texture_basisu, EXT_unheard_of, which this engine does not support");

  TestModel optional;
  optional.doc["extensionsUsed"] = {"KHR_materials_dispersion", "KHR_mesh_quantization"};
  optional.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  auto model = loadGltf(write(optional));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(hasWarning(*model, {"uses KHR_materials_dispersion, which this engine does not support; drawn without it"}))
      << allWarnings(*model);
  EXPECT_FALSE(hasWarning(*model, {"KHR_mesh_quantization"})) << allWarnings(*model);
}

}  // namespace
}  // namespace engine

namespace engine {
namespace {

// The test model with two morph targets on its primitive (both displace by the
// base positions, accessor 0), mesh weights, and a `weights` channel on node 0
// whose keys (accessor 7) are the first four rotation-key floats read as SCALAR:
// (0, 0) at t = 0 and (0, 1) at t = 1.
TestModel morphModel() {
  TestModel m;
  m.doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 0}}, {{"POSITION", 0}}};
  m.doc["meshes"][0]["weights"] = {0.5, 0.25};
  m.doc["accessors"].push_back({{"bufferView", 6}, {"componentType", 5126}, {"count", 4}, {"type", "SCALAR"}});
  m.doc["animations"][0]["samplers"].push_back({{"input", 5}, {"output", 7}});
  m.doc["animations"][0]["channels"].push_back({{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}});
  return m;
}

TEST_F(LoaderTest, LoadsMorphTargetsWeightsAndWeightChannels) {
  TestModel m = morphModel();
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  ASSERT_EQ(prim.morphTargets, 2);
  ASSERT_EQ(prim.morphPositions.size(), 6u);  // target-major: 2 targets x 3 vertices
  EXPECT_EQ(prim.morphPositions[4], glm::vec3(1, 0, 0));
  EXPECT_TRUE(prim.morphNormals.empty());
  EXPECT_EQ(model->meshes[0].morphWeights, (std::vector<float>{0.5f, 0.25f}));
  EXPECT_EQ(model->nodes[0].morphWeights, (std::vector<float>{0.5f, 0.25f}));  // the mesh's
  EXPECT_TRUE(model->nodes[1].morphWeights.empty());
  const AnimationData& anim = model->animations[0];
  EXPECT_EQ(anim.channels.size(), 1u);
  ASSERT_EQ(anim.morphChannels.size(), 1u);
  EXPECT_EQ(anim.morphChannels[0].node, 0);
  EXPECT_EQ(anim.morphChannels[0].targets, 2);
  EXPECT_EQ(anim.morphChannels[0].values, (std::vector<float>{0, 0, 0, 1}));
  auto pose = dumpPose(*model, 0, 1.0, LoopMode::Clamp);  // the last key, (0, 1)
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  EXPECT_EQ((*pose)["meshes"][0]["morphWeights"], nlohmann::json({0.0, 1.0}));
  EXPECT_EQ((*pose)["meshes"][0]["morphTargets"], 2);
}

TEST_F(LoaderTest, NodeWeightsOverrideTheMeshs) {
  TestModel m = morphModel();
  m.doc["nodes"][0]["weights"] = {1, -0.5};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->nodes[0].morphWeights, (std::vector<float>{1.0f, -0.5f}));
  EXPECT_EQ(model->meshes[0].morphWeights, (std::vector<float>{0.5f, 0.25f}));
  m.doc["meshes"][0].erase("weights");
  m.doc["nodes"][0].erase("weights");
  model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->nodes[0].morphWeights, (std::vector<float>{0.0f, 0.0f}));  // absent: zeros
}

TEST_F(LoaderTest, SparseMorphTargetWithoutABufferView) {
  TestModel m = morphModel();
  // Zeros, with vertex 0 (the u16 at byte 96) moved by (0, 1, 0) (bytes 248..259).
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 2}});
  m.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 248}, {"byteLength", 12}});
  m.doc["accessors"].push_back({{"componentType", 5126},
                                {"count", 3},
                                {"type", "VEC3"},
                                {"sparse",
                                 {{"count", 1},
                                  {"indices", {{"bufferView", 7}, {"componentType", 5123}}},
                                  {"values", {{"bufferView", 8}}}}}});
  m.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = 8;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const PrimitiveData& prim = model->meshes[0].primitives[0];
  EXPECT_EQ(prim.morphPositions[3], glm::vec3(0, 1, 0));
  EXPECT_EQ(prim.morphPositions[4], glm::vec3(0, 0, 0));
  EXPECT_EQ(prim.morphPositions[5], glm::vec3(0, 0, 0));
}

TEST_F(LoaderTest, UnmorphableTargetAttributesWarnAndAreIgnored) {
  TestModel m = morphModel();
  m.doc["meshes"][0]["primitives"][0]["targets"][0]["TEXCOORD_0"] = 0;
  m.doc["meshes"][0]["primitives"][0]["targets"][1]["NORMAL"] = 0;  // the primitive has no NORMAL
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(hasWarning(*model, {"mesh 0 primitive 0", "morph targets of NORMAL, TEXCOORD_0", "ignored"}))
      << allWarnings(*model);
  EXPECT_TRUE(model->meshes[0].primitives[0].morphNormals.empty());
  EXPECT_EQ(model->meshes[0].primitives[0].morphTargets, 2);
}

TEST_F(LoaderTest, PrimitivesOfOneMeshNeedTheSameTargetCount) {
  TestModel m = morphModel();
  json second = m.doc["meshes"][0]["primitives"][0];
  second["targets"] = {{{"POSITION", 0}}};
  m.doc["meshes"][0]["primitives"].push_back(second);
  expectError(write(m), {"mesh 0: primitive 1 has 1 morph targets, primitive 0 has 2"});
}

TEST_F(LoaderTest, WeightListsMustHaveOneEntryPerTarget) {
  TestModel m = morphModel();
  m.doc["meshes"][0]["weights"] = {0.5, 0.25, 1};
  expectError(write(m), {"mesh 0: weights has 3 entries for 2 morph targets"});
  m = morphModel();
  m.doc["nodes"][0]["weights"] = {1};
  expectError(write(m), {"node 0", "weights has 1 entries for 2 morph targets"});
  m = morphModel();
  m.doc["nodes"][1]["weights"] = {1, 0};
  expectError(write(m), {"node 1: has weights but no mesh"});
  m = morphModel();
  m.doc["meshes"][0].erase("primitives");
  m.doc["meshes"][0]["primitives"] = {{{"attributes", {{"POSITION", 0}}}}};
  m.doc["animations"][0]["channels"].erase(1);
  expectError(write(m), {"mesh 0: weights has 2 entries for 0 morph targets"});
}

TEST_F(LoaderTest, TargetAccessorsMustMatchTheBase) {
  TestModel m = morphModel();
  m.doc["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
  m.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = 8;
  expectError(write(m), {"mesh 0 primitive 0 target 1 POSITION", "has 2 elements, expected 3"});
  m = morphModel();
  m.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = 2;  // WEIGHTS_0: VEC4
  expectError(write(m), {"mesh 0 primitive 0 target 0 POSITION", "expected 3 components"});
  m = morphModel();
  m.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = 42;
  expectError(write(m), {"target 0 POSITION", "42"});
  m = morphModel();
  m.putFloat(4, std::numeric_limits<float>::quiet_NaN());  // vertex 0's y, read as a delta too
  expectError(write(m), {"NaN"});
}

TEST_F(LoaderTest, WeightChannelsAreChecked) {
  TestModel m = morphModel();
  m.doc["accessors"][7]["count"] = 3;
  expectError(write(m), {"animation 0 channel 1 sampler 1 output", "3 weights for 2 keys of 2 morph targets (4 expected)"});
  m = morphModel();
  m.doc["animations"][0]["samplers"][1]["interpolation"] = "CUBICSPLINE";  // needs 12
  expectError(write(m), {"sampler 1 output", "4 weights for 2 keys of 2 morph targets (12 expected)"});
  m = morphModel();
  m.doc["animations"][0]["channels"][1]["target"]["node"] = 1;
  expectError(write(m), {"animation 0 channel 1", "weights of node 1, which has no mesh"});
  m = morphModel();
  m.doc["meshes"][0]["primitives"][0].erase("targets");
  m.doc["meshes"][0].erase("weights");
  expectError(write(m), {"animation 0 channel 1", "weights of node 0, whose mesh 0 has no morph targets"});
  m = morphModel();
  m.doc["animations"][0]["samplers"][1]["interpolation"] = "SMOOTH";
  expectError(write(m), {"sampler 1", "unknown interpolation \"SMOOTH\""});
  m = morphModel();
  m.doc["animations"][0]["channels"].erase(0);  // the rotation channel reads the same floats
  m.putFloat(240 + 12, std::numeric_limits<float>::infinity());  // the key (0, 1)'s 1
  expectError(write(m), {"animation 0 channel 0 sampler 1 output", "NaN or infinite"});
}

// Many targets on one big zero-filled accessor cost a small file and could cost
// gigabytes: refused before anything is read.
TEST_F(LoaderTest, TooManyMorphDisplacements) {
  TestModel m = morphModel();
  const std::size_t vertices = 1u << 21;
  m.doc["accessors"].push_back({{"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {0, 0, 0}}});
  json prim = {{"attributes", {{"POSITION", 8}}}, {"targets", json::array()}};
  for (int t = 0; t < 9; ++t) prim["targets"].push_back({{"POSITION", 8}});
  m.doc["meshes"][0]["primitives"] = json::array({prim});  // not {prim}: clang reads that as a copy of prim
  m.doc["meshes"][0].erase("weights");
  m.doc["nodes"][0].erase("skin");
  m.doc["animations"][0]["channels"].erase(1);
  expectError(write(m), {"mesh 0 primitive 0", "9 morph targets of 2097152 vertices", "limit"});
}

// KHR_materials_emissive_strength multiplies emissiveFactor (supported: no warning);
// a negative or non-numeric strength is an error naming the material.
TEST_F(LoaderTest, EmissiveStrengthScalesTheEmissiveFactor) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  m.doc["materials"] = {{{"emissiveFactor", {1.0, 0.5, 0.0}},
                         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}},
                        {{"emissiveFactor", {0.25, 0.25, 0.25}}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->materials[0].emissiveFactor, glm::vec3(4.0f, 2.0f, 0.0f));
  EXPECT_EQ(model->materials[1].emissiveFactor, glm::vec3(0.25f));
  EXPECT_FALSE(hasWarning(*model, {"KHR_materials_emissive_strength"})) << allWarnings(*model);

  for (const nlohmann::json& bad : {nlohmann::json(-1.0), nlohmann::json("bright")}) {
    m.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = bad;
    auto refused = loadGltf(write(m));
    ASSERT_FALSE(refused.ok()) << bad.dump();
    EXPECT_NE(refused.error().message.find("material 0: KHR_materials_emissive_strength: emissiveStrength"),
              std::string::npos)
        << refused.error().message;
  }
}

// KHR_materials_unlit marks the material (supported, even when required: no
// warning, no refusal); a material without it stays lit.
TEST_F(LoaderTest, UnlitMaterialsAreMarked) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_unlit"};
  m.doc["extensionsRequired"] = {"KHR_materials_unlit"};
  m.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.5, 0.0, 1.0}}}},
                         {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}},
                        {{"emissiveFactor", {0.25, 0.25, 0.25}}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->materials[0].unlit);
  EXPECT_FALSE(model->materials[1].unlit);
  EXPECT_FALSE(hasWarning(*model, {"KHR_materials_unlit"})) << allWarnings(*model);
}

}  // namespace
}  // namespace engine

namespace engine {
namespace {

// KHR_materials_ior, _specular and _clearcoat become MaterialLayers (supported: no
// warning for the extensions); their textures are warned about by name; a value out
// of its range is an error naming the material, the extension and the key.
TEST_F(LoaderTest, ReadsTheDielectricLayers) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat"};
  m.doc["materials"] = {
      {{"extensions",
        {{"KHR_materials_ior", {{"ior", 1.33}}},
         {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 2.0}}}},
         {"KHR_materials_clearcoat",
          {{"clearcoatFactor", 0.75},
           {"clearcoatRoughnessFactor", 0.25},
           {"clearcoatTexture", {{"index", 0}}},
           {"clearcoatRoughnessTexture", {{"index", 7}}},
           {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}}}},
      {{"emissiveFactor", {0.25, 0.25, 0.25}}}};
  m.doc["materials"][0]["extensions"]["KHR_materials_specular"]["specularColorTexture"] = {
      {"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2.0, 3.0}}}}}}};
  m.doc["images"] = {{{"uri", "missing.png"}}};  // white, with its own warning
  m.doc["textures"] = {{{"source", 0}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialLayers& l = model->materials[0].layers;
  EXPECT_FLOAT_EQ(l.ior, 1.33f);
  EXPECT_FLOAT_EQ(l.specular, 0.5f);
  EXPECT_EQ(l.specularColor, glm::vec3(1.0f, 0.5f, 2.0f));
  EXPECT_FLOAT_EQ(l.clearcoat, 0.75f);
  EXPECT_FLOAT_EQ(l.clearcoatRoughness, 0.25f);
  // f0 = ((1.33 - 1) / 2.33)^2 = 0.02006 per channel, tinted, at most 1, times 0.5.
  const double r2 = std::pow(0.33 / 2.33, 2.0);
  EXPECT_NEAR(l.dielectricF0().x, r2 * 0.5, 1e-7);
  EXPECT_NEAR(l.dielectricF0().y, r2 * 0.25, 1e-7);
  EXPECT_NEAR(l.dielectricF0().z, r2, 1e-7);
  EXPECT_FLOAT_EQ(l.dielectricF90(), 0.5f);
  EXPECT_FALSE(l.isDefault());
  // The second material has none: exactly the plain model's 0.04.
  EXPECT_TRUE(model->materials[1].layers.isDefault());
  EXPECT_EQ(model->materials[1].layers.dielectricF0(), glm::vec3(0.04f));
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);
  // The layer textures are slots of their own, with their uv transforms; a texture
  // index that does not exist is dropped with a warning, as for the core slots.
  const MaterialData& mat = model->materials[0];
  EXPECT_EQ(mat.image(TextureSlot::Clearcoat), 0);
  EXPECT_EQ(mat.image(TextureSlot::SpecularColor), 0);
  EXPECT_EQ(mat.image(TextureSlot::ClearcoatRoughness), -1);
  EXPECT_EQ(mat.image(TextureSlot::Specular), -1);
  EXPECT_TRUE(mat.hasLayerTextures());
  EXPECT_TRUE(mat.layered());
  EXPECT_FLOAT_EQ(mat.texture(TextureSlot::SpecularColor).uvTransform[0][0], 2.0f);
  EXPECT_FLOAT_EQ(mat.texture(TextureSlot::SpecularColor).uvTransform[1][1], 3.0f);
  EXPECT_TRUE(hasWarning(*model, {"material 0", "KHR_materials_clearcoat: clearcoatRoughnessTexture 7 does not exist"}))
      << allWarnings(*model);
  // The coat's normal map is a slot of its own, with its scale.
  EXPECT_EQ(mat.image(TextureSlot::ClearcoatNormal), 0);
  EXPECT_FLOAT_EQ(mat.layers.clearcoatNormalScale, 0.5f);
  EXPECT_FALSE(hasWarning(*model, {"clearcoatNormalTexture"})) << allWarnings(*model);

  const std::vector<std::tuple<const char*, const char*, nlohmann::json>> bad = {
      {"KHR_materials_ior", "ior", 0.5},
      {"KHR_materials_ior", "ior", "glass"},
      {"KHR_materials_specular", "specularFactor", 1.5},
      {"KHR_materials_specular", "specularColorFactor", {1.0, -1.0, 0.0}},
      {"KHR_materials_clearcoat", "clearcoatFactor", -0.1},
      {"KHR_materials_clearcoat", "clearcoatRoughnessFactor", "smooth"},
  };
  expectMaterialValuesRefused(m, bad);
}

// KHR_materials_transmission and KHR_materials_volume: the factors, the two
// textures as slots of their own, absent attenuationDistance meaning "none
// absorbed" (0), and each key's range checked with the material named.
TEST_F(LoaderTest, ReadsTransmissionAndVolume) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
  m.doc["materials"] = {
      {{"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 0.8}, {"transmissionTexture", {{"index", 0}}}}},
         {"KHR_materials_volume",
          {{"thicknessFactor", 0.25},
           {"thicknessTexture", {{"index", 0}, {"texCoord", 1}}},
           {"attenuationDistance", 2.0},
           {"attenuationColor", {0.9, 0.5, 0.1}}}}}}},
      {{"extensions", {{"KHR_materials_transmission", json::object()}, {"KHR_materials_volume", json::object()}}}}};
  m.doc["images"] = {{{"uri", "missing.png"}}};
  m.doc["textures"] = {{{"source", 0}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialLayers& l = model->materials[0].layers;
  EXPECT_FLOAT_EQ(l.transmission, 0.8f);
  EXPECT_FLOAT_EQ(l.thickness, 0.25f);
  EXPECT_FLOAT_EQ(l.attenuationDistance, 2.0f);
  EXPECT_EQ(l.attenuationColor, glm::vec3(0.9f, 0.5f, 0.1f));
  EXPECT_TRUE(l.transmissive());
  EXPECT_FALSE(l.isDefault());
  const MaterialData& mat = model->materials[0];
  EXPECT_EQ(mat.image(TextureSlot::Transmission), 0);
  EXPECT_EQ(mat.image(TextureSlot::Thickness), 0);
  EXPECT_EQ(mat.texture(TextureSlot::Thickness).texCoord, 1);
  // The defaults: nothing transmitted, thin-walled, nothing absorbed.
  const MaterialLayers& d = model->materials[1].layers;
  EXPECT_FALSE(d.transmissive());
  EXPECT_EQ(d.thickness, 0.0f);
  EXPECT_EQ(d.attenuationDistance, 0.0f);
  EXPECT_EQ(d.attenuationColor, glm::vec3(1.0f));
  EXPECT_TRUE(d.isDefault());
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);

  const std::vector<std::tuple<const char*, const char*, nlohmann::json>> bad = {
      {"KHR_materials_transmission", "transmissionFactor", 1.5},
      {"KHR_materials_transmission", "transmissionFactor", "clear"},
      {"KHR_materials_volume", "thicknessFactor", -1.0},
      {"KHR_materials_volume", "attenuationDistance", 0.0},
      {"KHR_materials_volume", "attenuationColor", {1.0, 2.0, 0.0}},
      {"KHR_materials_volume", "attenuationColor", {1.0, 1.0}},
  };
  expectMaterialValuesRefused(m, bad);
}

// KHR_materials_sheen: colour and roughness, black (no sheen) when absent, the two
// textures as slots of their own (the colour's sRGB), and each key's range checked
// with the material named.
TEST_F(LoaderTest, ReadsSheen) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  m.doc["materials"] = {{{"extensions",
                          {{"KHR_materials_sheen",
                            {{"sheenColorFactor", {0.9, 0.5, 0.1}},
                             {"sheenColorTexture", {{"index", 0}}},
                             {"sheenRoughnessFactor", 0.3},
                             {"sheenRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}}}}},
                        {{"extensions", {{"KHR_materials_sheen", json::object()}}}}};
  m.doc["images"] = {{{"uri", "missing.png"}}};
  m.doc["textures"] = {{{"source", 0}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialData& mat = model->materials[0];
  EXPECT_EQ(mat.layers.sheenColor, glm::vec3(0.9f, 0.5f, 0.1f));
  EXPECT_FLOAT_EQ(mat.layers.sheenRoughness, 0.3f);
  EXPECT_TRUE(mat.layers.sheen());
  EXPECT_FALSE(mat.layers.isDefault());
  EXPECT_EQ(mat.image(TextureSlot::SheenColor), 0);
  EXPECT_EQ(mat.image(TextureSlot::SheenRoughness), 0);
  EXPECT_EQ(mat.texture(TextureSlot::SheenRoughness).texCoord, 1);
  EXPECT_TRUE(isSrgbSlot(TextureSlot::SheenColor));
  EXPECT_FALSE(isSrgbSlot(TextureSlot::SheenRoughness));
  // The default is no sheen at all: the plain material.
  const MaterialLayers& d = model->materials[1].layers;
  EXPECT_FALSE(d.sheen());
  EXPECT_TRUE(d.isDefault());
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);

  const std::vector<std::tuple<const char*, const char*, nlohmann::json>> bad = {
      {"KHR_materials_sheen", "sheenColorFactor", {1.0, 1.5, 0.0}},
      {"KHR_materials_sheen", "sheenColorFactor", "white"},
      {"KHR_materials_sheen", "sheenRoughnessFactor", -0.5},
      {"KHR_materials_sheen", "sheenRoughnessFactor", 2.0},
  };
  expectMaterialValuesRefused(m, bad);
}

// KHR_materials_anisotropy: strength, rotation and texture; a primitive that cannot
// have tangents built is warned about (the stretch is oriented by them), and each
// key's range checked with the material named.
TEST_F(LoaderTest, ReadsAnisotropy) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_anisotropy"};
  m.doc["materials"] = {{{"extensions",
                          {{"KHR_materials_anisotropy",
                            {{"anisotropyStrength", 0.6}, {"anisotropyRotation", 1.25}, {"anisotropyTexture", {{"index", 0}}}}}}}}};
  m.doc["images"] = {{{"uri", "missing.png"}}};
  m.doc["textures"] = {{{"source", 0}}};
  m.doc["meshes"][0]["primitives"][0]["material"] = 0;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialData& mat = model->materials[0];
  EXPECT_FLOAT_EQ(mat.layers.anisotropy, 0.6f);
  EXPECT_FLOAT_EQ(mat.layers.anisotropyRotation, 1.25f);
  EXPECT_FALSE(mat.layers.isDefault());
  EXPECT_EQ(mat.image(TextureSlot::Anisotropy), 0);
  EXPECT_FALSE(isSrgbSlot(TextureSlot::Anisotropy));
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);
  // The test model's triangle has neither NORMAL nor TEXCOORD_0: no tangents to
  // orient the stretch by, said so.
  EXPECT_TRUE(model->meshes[0].primitives[0].tangents.empty());
  EXPECT_TRUE(hasWarning(*model, {"anisotropy needs NORMAL, TEXCOORD_0 and triangles to build tangents"}))
      << allWarnings(*model);

  const std::vector<std::tuple<const char*, const char*, nlohmann::json>> bad = {
      {"KHR_materials_anisotropy", "anisotropyStrength", 1.5},
      {"KHR_materials_anisotropy", "anisotropyStrength", -0.1},
      {"KHR_materials_anisotropy", "anisotropyRotation", "left"},
  };
  expectMaterialValuesRefused(m, bad);
}

// KHR_materials_iridescence: the film's share, index and thickness range with their
// defaults (1.3, 100-400 nm), the two textures as slots of their own, and each key's
// range checked with the material named.
TEST_F(LoaderTest, ReadsIridescence) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_iridescence"};
  m.doc["extensionsRequired"] = {"KHR_materials_iridescence"};
  m.doc["materials"] = {{{"extensions",
                          {{"KHR_materials_iridescence",
                            {{"iridescenceFactor", 0.8},
                             {"iridescenceIor", 1.8},
                             {"iridescenceThicknessMinimum", 200.0},
                             {"iridescenceThicknessMaximum", 600.0},
                             {"iridescenceTexture", {{"index", 0}}},
                             {"iridescenceThicknessTexture", {{"index", 0}}}}}}}},
                        {{"extensions", {{"KHR_materials_iridescence", {{"iridescenceFactor", 1.0}}}}}}};
  m.doc["images"] = {{{"uri", "missing.png"}}};
  m.doc["textures"] = {{{"source", 0}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const MaterialLayers& l = model->materials[0].layers;
  EXPECT_FLOAT_EQ(l.iridescence, 0.8f);
  EXPECT_FLOAT_EQ(l.iridescenceIor, 1.8f);
  EXPECT_FLOAT_EQ(l.iridescenceThicknessMin, 200.0f);
  EXPECT_FLOAT_EQ(l.iridescenceThicknessMax, 600.0f);
  EXPECT_FALSE(l.isDefault());
  EXPECT_EQ(model->materials[0].image(TextureSlot::Iridescence), 0);
  EXPECT_EQ(model->materials[0].image(TextureSlot::IridescenceThickness), 0);
  const MaterialLayers& d = model->materials[1].layers;
  EXPECT_FLOAT_EQ(d.iridescenceIor, 1.3f);
  EXPECT_FLOAT_EQ(d.iridescenceThicknessMin, 100.0f);
  EXPECT_FLOAT_EQ(d.iridescenceThicknessMax, 400.0f);
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);

  const std::vector<std::tuple<const char*, const char*, nlohmann::json>> bad = {
      {"KHR_materials_iridescence", "iridescenceFactor", 1.2},
      {"KHR_materials_iridescence", "iridescenceIor", 0.5},
      {"KHR_materials_iridescence", "iridescenceThicknessMinimum", -10.0},
      {"KHR_materials_iridescence", "iridescenceThicknessMaximum", "thick"},
  };
  expectMaterialValuesRefused(m, bad);
}

// KHR_materials_variants: the root's names, each primitive's mapping of variants to
// materials, a model remapped to one variant (the others keep their material), and
// mappings that point nowhere refused with the primitive and mapping named.
TEST_F(LoaderTest, ReadsMaterialVariants) {
  TestModel m;
  m.doc["extensionsUsed"] = {"KHR_materials_variants"};
  m.doc["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}, {{"name", "blue"}}, {{"name", "plain"}}};
  m.doc["materials"] = {{{"name", "default"}}, {{"name", "red"}}, {{"name", "blue"}}};
  m.doc["meshes"][0]["primitives"][0]["material"] = 0;
  m.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}};
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->variants, (std::vector<std::string>{"red", "blue", "plain"}));
  EXPECT_EQ(model->meshes[0].primitives[0].variantMaterials, (std::vector<int>{1, 2, -1}));
  EXPECT_FALSE(hasWarning(*model, {"does not support"})) << allWarnings(*model);
  EXPECT_EQ(findVariant(*model, "blue"), 1);
  EXPECT_EQ(findVariant(*model, "2"), 2);
  EXPECT_EQ(findVariant(*model, "green"), std::nullopt);
  EXPECT_EQ(findVariant(*model, "3"), std::nullopt);
  EXPECT_EQ(withVariant(*model, 0).meshes[0].primitives[0].material, 1);
  EXPECT_EQ(withVariant(*model, 1).meshes[0].primitives[0].material, 2);
  EXPECT_EQ(withVariant(*model, 2).meshes[0].primitives[0].material, 0);
  EXPECT_EQ(withVariant(*model, -1).meshes[0].primitives[0].material, 0);

  const std::pair<json, std::string> bad[] = {
      {{{{"material", 7}, {"variants", {0}}}}, "mapping 0: material 7 does not exist"},
      {{{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {5}}}}, "mapping 1: variant 5 does not exist"},
      {{{{"material", 1}}}, "mapping 0: needs a \"material\" index and a \"variants\" list"},
  };
  for (const auto& [mappings, message] : bad) {
    TestModel broken = m;
    broken.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = mappings;
    auto refused = loadGltf(write(broken));
    ASSERT_FALSE(refused.ok()) << mappings.dump();
    EXPECT_NE(refused.error().message.find("mesh 0 primitive 0: KHR_materials_variants: " + message), std::string::npos)
        << refused.error().message;
  }
  TestModel undeclared = m;
  undeclared.doc["extensions"].erase("KHR_materials_variants");
  auto refused = loadGltf(write(undeclared));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("the file declares no variants"), std::string::npos) << refused.error().message;
}

// glTF cameras: perspective and orthographic read with their node; values out of
// glTF's range refused, naming the camera.
TEST_F(LoaderTest, ReadsCameras) {
  TestModel m;
  m.doc["cameras"] = {{{"type", "perspective"}, {"name", "eye"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.05}, {"zfar", 80.0}}}},
                      {{"type", "orthographic"}, {"orthographic", {{"xmag", 2.0}, {"ymag", 1.5}, {"znear", 0.0}, {"zfar", 10.0}}}}};
  m.doc["nodes"][1]["camera"] = 0;
  auto model = loadGltf(write(m));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->cameras.size(), 2u);
  EXPECT_EQ(model->cameras[0].name, "eye");
  EXPECT_TRUE(model->cameras[0].perspective);
  EXPECT_FLOAT_EQ(model->cameras[0].yfov, 0.6f);
  EXPECT_FLOAT_EQ(model->cameras[0].znear, 0.05f);
  EXPECT_FLOAT_EQ(model->cameras[0].zfar, 80.0f);
  EXPECT_FALSE(model->cameras[1].perspective);
  EXPECT_FLOAT_EQ(model->cameras[1].ymag, 1.5f);
  EXPECT_EQ(model->nodes[1].camera, 0);
  EXPECT_EQ(model->nodes[0].camera, -1);

  const std::tuple<int, const char*, double, std::string> bad[] = {
      {0, "yfov", 4.0, "camera 0 (\"eye\"): yfov must be in (0, pi)"},
      {0, "zfar", 0.01, "camera 0 (\"eye\"): zfar must be > znear"},
      {1, "xmag", 0.0, "camera 1: xmag and ymag must be finite and not 0"},
  };
  for (const auto& [camera, key, value, message] : bad) {
    TestModel broken = m;
    broken.doc["cameras"][camera][camera == 0 ? "perspective" : "orthographic"][key] = value;
    auto refused = loadGltf(write(broken));
    ASSERT_FALSE(refused.ok()) << key;
    EXPECT_NE(refused.error().message.find(message), std::string::npos) << refused.error().message;
  }
  TestModel nowhere = m;
  nowhere.doc["nodes"][1]["camera"] = 5;
  auto refused = loadGltf(write(nowhere));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("node 1: camera 5 does not exist"), std::string::npos) << refused.error().message;
}

}  // namespace
}  // namespace engine
