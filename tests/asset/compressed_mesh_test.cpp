// Compressed and quantized glTF geometry: KHR_draco_mesh_compression and
// KHR_mesh_quantization samples (../shared/gltf-samples) against the uncompressed
// versions of the same models, EXT_meshopt_compression written here with
// meshoptimizer's encoders (decoded back exactly) and by gltfpack
// (tests/data/meshopt), and broken streams of both compressions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <dlfcn.h>

#include <glm/gtc/matrix_transform.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "asset/draco_mesh.h"
#include "asset/gltf_loader.h"
#include "../support/files.h"

extern "C" void stbi_image_free(void* pixels);  // stb_image.h, without its implementation macros

namespace engine {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kSamples = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/";

// ---- geometry of a whole model, in world space ----------------------------------

glm::mat4 localMatrix(const NodeData& n) {
  return glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::mat4(1.0f), n.scale);
}

// Calls `visit(node, world)` for every node of the default scene.
void forEachNode(const ModelData& model, const std::function<void(const NodeData&, const glm::mat4&)>& visit) {
  std::function<void(int, const glm::mat4&)> walk = [&](int n, const glm::mat4& parent) {
    const NodeData& node = model.nodes[static_cast<std::size_t>(n)];
    const glm::mat4 world = parent * localMatrix(node);
    visit(node, world);
    for (int c : node.children) walk(c, world);
  };
  for (int root : model.sceneRoots) walk(root, glm::mat4(1.0f));
}

struct Geometry {
  glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
  std::size_t triangles = 0, primitives = 0, morphTargets = 0;
  double area = 0.0, perimeter = 0.0;
  double maxScale = 0.0;  // the largest axis scale of any world matrix with a mesh
};

// The triangles of every primitive as drawn at rest (no morph weights applied).
Geometry geometry(const ModelData& model) {
  Geometry g;
  forEachNode(model, [&](const NodeData& node, const glm::mat4& world) {
    if (node.mesh < 0) return;
    for (int c = 0; c < 3; ++c) g.maxScale = std::max(g.maxScale, double(glm::length(glm::vec3(world[c]))));
    for (const PrimitiveData& prim : model.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
      ++g.primitives;
      g.morphTargets += static_cast<std::size_t>(prim.morphTargets);
      std::vector<glm::dvec3> p;
      for (const glm::vec3& v : prim.positions) {
        p.push_back(glm::dvec3(world * glm::vec4(v, 1.0f)));
        g.lo = glm::min(g.lo, p.back());
        g.hi = glm::max(g.hi, p.back());
      }
      if (prim.mode != 4) continue;
      auto corner = [&](std::size_t i) { return prim.indices.empty() ? i : std::size_t{prim.indices[i]}; };
      const std::size_t corners = prim.indices.empty() ? p.size() : prim.indices.size();
      for (std::size_t t = 0; t + 2 < corners; t += 3) {
        const glm::dvec3 a = p[corner(t)], b = p[corner(t + 1)], c = p[corner(t + 2)];
        ++g.triangles;
        g.area += 0.5 * glm::length(glm::cross(b - a, c - a));
        g.perimeter += glm::distance(a, b) + glm::distance(b, c) + glm::distance(c, a);
      }
    }
  });
  return g;
}

// The world matrix of the first node of the default scene that draws mesh `mesh`.
glm::mat4 meshWorld(const ModelData& model, int mesh) {
  glm::mat4 found(1.0f);
  bool seen = false;
  forEachNode(model, [&](const NodeData& node, const glm::mat4& world) {
    if (node.mesh == mesh && !seen) found = world, seen = true;
  });
  return found;
}

// `quantized` against `reference` when every vertex of `quantized` lies within
// `epsilon` (a length, world units) of where the reference has it.
//
// Bounds: each face of the box moves by at most epsilon.
// Area: move a triangle's corners one at a time. Moving a by at most epsilon
// changes its height over the opposite edge bc by at most epsilon, so the area by
// at most epsilon |bc| / 2; then b, over an edge a'c at most epsilon longer than
// ac; then c, over a'b' at most 2 epsilon longer than ab. In all at most
// epsilon P_t / 2 + 3 epsilon^2 / 2 for a triangle of perimeter P_t, and
// epsilon P / 2 + 3 T epsilon^2 / 2 for the model (P: total perimeter, T:
// triangles). That bound is strict; the 1e-6 relative slack is float rounding.
void expectSameGeometry(const Geometry& quantized, const Geometry& reference, double epsilon) {
  EXPECT_EQ(quantized.primitives, reference.primitives);
  EXPECT_EQ(quantized.triangles, reference.triangles);
  EXPECT_EQ(quantized.morphTargets, reference.morphTargets);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(quantized.lo[c], reference.lo[c], epsilon) << "axis " << c;
    EXPECT_NEAR(quantized.hi[c], reference.hi[c], epsilon) << "axis " << c;
  }
  const double areaTolerance = 0.5 * epsilon * reference.perimeter +
                               1.5 * double(reference.triangles) * epsilon * epsilon + 1e-6 * reference.area;
  EXPECT_NEAR(quantized.area, reference.area, areaTolerance)
      << "epsilon " << epsilon << ", perimeter " << reference.perimeter;
  // A decoder that got the scale or the vertex order wrong is far outside it.
  EXPECT_LT(areaTolerance, 0.05 * reference.area);
  std::printf("area %.6f vs %.6f (difference %.2e, bound %.2e); epsilon %.2e\n", quantized.area, reference.area,
              std::abs(quantized.area - reference.area), areaTolerance, epsilon);
}

// ---- KHR_draco_mesh_compression -------------------------------------------------

// The largest quantization step of the POSITION attribute over every Draco
// primitive of a .gltf (model units), as the stream itself records it.
double dracoPositionStep(const fs::path& gltf) {
  const json doc = json::parse(std::ifstream(gltf));
  const auto bin = test::readBytes(gltf.parent_path() / doc["buffers"][0]["uri"].get<std::string>());
  double step = 0.0;
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      const auto& ext = prim["extensions"]["KHR_draco_mesh_compression"];
      const auto& view = doc["bufferViews"][ext["bufferView"].get<std::size_t>()];
      const std::span bytes(bin.data() + view.value("byteOffset", std::size_t{0}), view["byteLength"].get<std::size_t>());
      auto q = gltf::DracoMesh::quantizationStep(bytes, ext["attributes"]["POSITION"].get<std::uint32_t>());
      EXPECT_TRUE(q.ok()) << gltf << ": " << q.error().message;
      if (q.ok()) step = std::max(step, *q);
    }
  return step;
}

struct CompressedCase {
  const char* compressed;  // under ../shared/gltf-samples
  const char* reference;
};

// The test name: the sample's folder ("Duck").
std::string sampleName(const ::testing::TestParamInfo<CompressedCase>& param) {
  const std::string path = param.param.compressed;
  return path.substr(0, path.find('/'));
}

class DracoSampleTest : public ::testing::TestWithParam<CompressedCase> {};

// Draco keeps every triangle but may reorder and merge the points, so the decoded
// model is compared by what it covers: triangle counts, world bounds and area. A
// point moves by at most half a quantization step per axis, sqrt(3) / 2 steps in
// all, scaled by the node transforms (maxScale).
TEST_P(DracoSampleTest, DecodesToTheUncompressedGeometry) {
  const fs::path compressed = kSamples + GetParam().compressed, reference = kSamples + GetParam().reference;
  if (!fs::exists(compressed)) GTEST_SKIP() << compressed << " not found (../shared/gltf-samples absent)";
  auto draco = loadGltf(compressed.string());
  ASSERT_TRUE(draco.ok()) << draco.error().message;
  auto plain = loadGltf(reference.string());
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  for (const std::string& w : draco->warnings) EXPECT_EQ(w.find("KHR_draco"), std::string::npos) << w;
  const double step = dracoPositionStep(compressed);
  ASSERT_GT(step, 0.0);
  const Geometry g = geometry(*draco), ref = geometry(*plain);
  const double epsilon = std::sqrt(3.0) / 2.0 * step * g.maxScale;
  expectSameGeometry(g, ref, epsilon);
  // Morph targets stay uncompressed and are read per decoded point: they must
  // still line up with the positions.
  for (const MeshData& mesh : draco->meshes)
    for (const PrimitiveData& prim : mesh.primitives) {
      EXPECT_EQ(prim.morphPositions.size(), std::size_t(prim.morphTargets) * prim.positions.size());
      EXPECT_EQ(prim.normals.size(), prim.positions.size());
      for (std::uint32_t i : prim.indices) ASSERT_LT(i, prim.positions.size());
    }
}

INSTANTIATE_TEST_SUITE_P(
    Samples, DracoSampleTest,
    ::testing::Values(CompressedCase{"Box/glTF-Draco/Box.gltf", "Box/glTF-Binary/Box.glb"},
                      CompressedCase{"Duck/glTF-Draco/Duck.gltf", "Duck/glTF-Binary/Duck.glb"},
                      CompressedCase{"CesiumMilkTruck/glTF-Draco/CesiumMilkTruck.gltf",
                                     "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"},
                      CompressedCase{"MorphPrimitivesTest/glTF-Draco/MorphPrimitivesTest.gltf",
                                     "MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb"}),
    sampleName);

// A copy of the Draco Box with its compressed stream cut or overwritten.
class DracoCorruptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    source_ = kSamples + "Box/glTF-Draco";
    if (!fs::exists(source_)) GTEST_SKIP() << source_ << " not found (../shared/gltf-samples absent)";
    dir_ = fs::temp_directory_path() / ("engine_draco_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    doc_ = json::parse(std::ifstream(source_ / "Box.gltf"));
    bin_ = test::readBytes(source_ / "Box.bin");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write() {
    std::ofstream(dir_ / "Box.bin", std::ios::binary).write(reinterpret_cast<const char*>(bin_.data()), std::streamsize(bin_.size()));
    std::ofstream(dir_ / "Box.gltf") << doc_.dump();
    return (dir_ / "Box.gltf").string();
  }
  json& dracoView() {
    return doc_["bufferViews"][doc_["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<std::size_t>()];
  }
  fs::path source_, dir_;
  json doc_;
  std::vector<unsigned char> bin_;
};

TEST_F(DracoCorruptTest, TruncatedStreamNamesTheFileAndPrimitive) {
  dracoView()["byteLength"] = dracoView()["byteLength"].get<int>() / 2;
  const std::string path = write();
  auto model = loadGltf(path);
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.error().message.rfind(path + ": mesh 0 primitive 0: KHR_draco_mesh_compression: decode failed: ", 0), 0u)
      << model.error().message;
}

TEST_F(DracoCorruptTest, OverwrittenStreamIsAnErrorNotACrash) {
  // Every run of 8 bytes in turn zeroed: the decoder must refuse or decode, and
  // a decoded mesh must still pass the loader's own checks.
  const std::size_t offset = dracoView().value("byteOffset", 0), length = dracoView()["byteLength"];
  const std::vector<unsigned char> original = bin_;
  int refused = 0;
  for (std::size_t at = 0; at < length; at += 8) {
    bin_ = original;
    std::fill_n(bin_.begin() + std::ptrdiff_t(offset + at), std::min<std::size_t>(8, length - at), 0xFF);
    auto model = loadGltf(write());
    if (!model.ok()) {
      ++refused;
      EXPECT_NE(model.error().message.find("Box.gltf: mesh 0 primitive 0"), std::string::npos) << model.error().message;
    }
  }
  EXPECT_GT(refused, 0);
}

TEST_F(DracoCorruptTest, UnknownAttributeIdAndMissingIndices) {
  doc_["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 42;
  auto model = loadGltf(write());
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("mesh 0 primitive 0: KHR_draco_mesh_compression: NORMAL: Draco attribute 42 is not in the data"),
            std::string::npos) << model.error().message;
  doc_ = json::parse(std::ifstream(source_ / "Box.gltf"));
  doc_["meshes"][0]["primitives"][0].erase("indices");
  model = loadGltf(write());
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("KHR_draco_mesh_compression: the primitive has no indices"), std::string::npos)
      << model.error().message;
}

// ---- KHR_mesh_quantization --------------------------------------------------------

// The quantization step of every POSITION accessor (the glTF-Quantized samples
// keep the uncompressed vertex order, so vertices are also compared one by one).
double quantizedPositionStep(const fs::path& gltf) {
  const json doc = json::parse(std::ifstream(gltf));
  double step = 0.0;
  auto stepOf = [](const json& accessor) {
    const bool normalized = accessor.value("normalized", false);
    switch (accessor["componentType"].get<int>()) {
      case 5120: return normalized ? 1.0 / 127.0 : 1.0;
      case 5121: return normalized ? 1.0 / 255.0 : 1.0;
      case 5122: return normalized ? 1.0 / 32767.0 : 1.0;
      case 5123: return normalized ? 1.0 / 65535.0 : 1.0;
      default: return 0.0;  // float: only float rounding
    }
  };
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      step = std::max(step, stepOf(doc["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()]));
      for (const auto& target : prim.value("targets", json::array()))
        if (target.contains("POSITION")) step = std::max(step, stepOf(doc["accessors"][target["POSITION"].get<std::size_t>()]));
    }
  return step;
}

class QuantizedSampleTest : public ::testing::TestWithParam<CompressedCase> {};

TEST_P(QuantizedSampleTest, DecodesToTheUnquantizedGeometry) {
  const fs::path quantized = kSamples + GetParam().compressed, reference = kSamples + GetParam().reference;
  if (!fs::exists(quantized)) GTEST_SKIP() << quantized << " not found (../shared/gltf-samples absent)";
  auto q = loadGltf(quantized.string());
  ASSERT_TRUE(q.ok()) << q.error().message;
  auto plain = loadGltf(reference.string());
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  const double step = quantizedPositionStep(quantized);
  ASSERT_GT(step, 0.0);
  const Geometry g = geometry(*q), ref = geometry(*plain);
  // Rounded to the nearest step: half a step per axis; plus float rounding of
  // the reference's own (world-space) coordinates.
  const double epsilon = std::sqrt(3.0) / 2.0 * step * g.maxScale + 1e-5 * glm::length(ref.hi - ref.lo);
  expectSameGeometry(g, ref, epsilon);

  // Every vertex has a counterpart in the reference (gltfpack reordered them):
  // a vertex within epsilon of it whose normal is within two steps of a signed
  // normalized byte (the coarsest the samples use) and whose texture coordinate,
  // through the material's KHR_texture_transform (which undoes its scale), is
  // within 1e-3. A wrongly normalized NORMAL or TEXCOORD_0 finds none.
  ASSERT_EQ(q->meshes.size(), plain->meshes.size());
  std::size_t matched = 0;
  for (std::size_t m = 0; m < q->meshes.size(); ++m) {
    ASSERT_EQ(q->meshes[m].primitives.size(), plain->meshes[m].primitives.size());
    for (std::size_t p = 0; p < q->meshes[m].primitives.size(); ++p) {
      const PrimitiveData& a = q->meshes[m].primitives[p];
      const PrimitiveData& b = plain->meshes[m].primitives[p];
      ASSERT_EQ(a.normals.empty(), b.normals.empty());
      ASSERT_EQ(a.uvs.empty(), b.uvs.empty());
      ASSERT_EQ(a.morphPositions.size() / std::max<std::size_t>(1, a.positions.size()),
                b.morphPositions.size() / std::max<std::size_t>(1, b.positions.size()));
      const glm::mat3 uvTransform =
          a.material < 0 ? glm::mat3(1.0f) : q->materials[std::size_t(a.material)].texture(TextureSlot::BaseColor).uvTransform;
      const glm::mat4 worldA = meshWorld(*q, int(m)), worldB = meshWorld(*plain, int(m));
      for (std::size_t i = 0; i < a.positions.size(); ++i) {
        const glm::vec3 pa(worldA * glm::vec4(a.positions[i], 1.0f));
        bool found = false;
        for (std::size_t j = 0; j < b.positions.size() && !found; ++j) {
          if (glm::distance(pa, glm::vec3(worldB * glm::vec4(b.positions[j], 1.0f))) > epsilon) continue;
          const bool normal = a.normals.empty() ||
                              glm::distance(glm::normalize(a.normals[i]), glm::normalize(b.normals[j])) < 2.0f * std::sqrt(3.0f) / 127.0f;
          const bool uv = a.uvs.empty() || glm::distance(glm::vec2(uvTransform * glm::vec3(a.uvs[i], 1.0f)), b.uvs[j]) < 1e-3f;
          found = normal && uv;
        }
        ASSERT_TRUE(found) << "mesh " << m << " primitive " << p << " vertex " << i << " has no counterpart";
        ++matched;
      }
    }
  }
  EXPECT_GT(matched, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, QuantizedSampleTest,
    ::testing::Values(CompressedCase{"Duck/glTF-Quantized/Duck.gltf", "Duck/glTF-Binary/Duck.glb"},
                      CompressedCase{"AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf",
                                     "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb"}),
    sampleName);

// ---- linking ------------------------------------------------------------------------

// Debian's libdraco.so exports bundled copies of tinygltf and stb_image; linked
// the wrong way (shared, or before libtinygltf and libstb) they replace the real
// ones and every load corrupts memory. engine/asset/CMakeLists.txt links
// libdraco.a after both; this fails if either resolves anywhere else.
std::string libraryOf(const void* address) {
  Dl_info info{};
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) return "(unknown)";
  return info.dli_fname;
}

template <typename F>
const void* addressOf(F* function) {
  const void* address = nullptr;
  std::memcpy(&address, &function, sizeof address);
  return address;
}

TEST(CompressedMeshLinking, TinygltfAndStbComeFromTheirLibraries) {
  EXPECT_NE(libraryOf(addressOf(&tinygltf::FileExists)).find("libtinygltf"), std::string::npos)
      << libraryOf(addressOf(&tinygltf::FileExists));
  EXPECT_NE(libraryOf(addressOf(&stbi_image_free)).find("libstb"), std::string::npos)
      << libraryOf(addressOf(&stbi_image_free));
}

// ---- EXT_meshopt_compression --------------------------------------------------------

// One bufferView of the meshopt test model: the bytes a loader must end up with
// (`plain`: what meshoptimizer's own decoder and filter give) and their encoding.
struct Stream {
  std::vector<unsigned char> plain, packed;
  std::size_t count = 0, stride = 0;
  std::string mode, filter = "NONE";
  std::size_t viewStride = 0;  // byteStride of the bufferView (vertex attributes only)
  std::size_t plainOffset = 0, packedOffset = 0;
};

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values) {
  std::vector<unsigned char> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// `filtered`: vertex data as meshopt_encodeFilter* left it (or plain, filter NONE).
Stream attributeStream(std::vector<unsigned char> filtered, std::size_t stride, const std::string& filter,
                       std::size_t viewStride = 0) {
  Stream s;
  s.count = filtered.size() / stride;
  s.stride = stride;
  s.mode = "ATTRIBUTES";
  s.filter = filter;
  s.viewStride = viewStride;
  s.packed.resize(meshopt_encodeVertexBufferBound(s.count, stride));
  s.packed.resize(meshopt_encodeVertexBuffer(s.packed.data(), s.packed.size(), filtered.data(), s.count, stride));
  if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(filtered.data(), s.count, stride);
  if (filter == "QUATERNION") meshopt_decodeFilterQuat(filtered.data(), s.count, stride);
  if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(filtered.data(), s.count, stride);
  s.plain = std::move(filtered);
  return s;
}

// TRIANGLES (meshopt_encodeIndexBuffer) or INDICES (meshopt_encodeIndexSequence),
// decoded to 16-bit (`stride` 2) or 32-bit indices.
Stream indexStream(const std::vector<std::uint32_t>& indices, const std::string& mode, std::size_t stride,
                   std::size_t vertices) {
  Stream s;
  s.count = indices.size();
  s.stride = stride;
  s.mode = mode;
  if (mode == "TRIANGLES") {
    s.packed.resize(meshopt_encodeIndexBufferBound(s.count, vertices));
    s.packed.resize(meshopt_encodeIndexBuffer(s.packed.data(), s.packed.size(), indices.data(), s.count));
  } else {
    s.packed.resize(meshopt_encodeIndexSequenceBound(s.count, vertices));
    s.packed.resize(meshopt_encodeIndexSequence(s.packed.data(), s.packed.size(), indices.data(), s.count));
  }
  if (stride == 4) s.plain = bytesOf(indices);
  else s.plain = bytesOf(std::vector<std::uint16_t>(indices.begin(), indices.end()));
  return s;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t{bytes[i + 1]} << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    const std::size_t present = std::min<std::size_t>(3, bytes.size() - i);  // 1 to 3 bytes: 2 to 4 digits
    for (std::size_t k = 0; k < 4; ++k) out += k <= present ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::vector<unsigned char> glbOf(const json& doc, const std::vector<unsigned char>& bin) {
  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  std::vector<unsigned char> body(bin);
  body.resize((body.size() + 3) & ~std::size_t{3}, 0);
  const std::uint32_t header[5] = {0x46546C67, 2, std::uint32_t(28 + text.size() + body.size()), std::uint32_t(text.size()),
                                   0x4E4F534A};
  const std::uint32_t binHeader[2] = {std::uint32_t(body.size()), 0x004E4942};
  std::vector<unsigned char> out(sizeof header + text.size() + sizeof binHeader + body.size());
  std::memcpy(out.data(), header, sizeof header);
  std::memcpy(out.data() + sizeof header, text.data(), text.size());
  std::memcpy(out.data() + sizeof header + text.size(), binHeader, sizeof binHeader);
  std::memcpy(out.data() + sizeof header + text.size() + sizeof binHeader, body.data(), body.size());
  return out;
}

// A 9 x 9 grid with every meshopt mode and filter: float positions (ATTRIBUTES),
// octahedral 8-bit normals, exponential uvs, a TRIANGLES and an INDICES
// primitive, and a rotation channel whose keys are QUATERNION-filtered.
class MeshoptModel {
 public:
  MeshoptModel() {
    const int n = 9;
    std::vector<float> positions, normals, uvs;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float fx = float(x) / (n - 1), fy = float(y) / (n - 1);
        positions.insert(positions.end(), {fx * 2.0f - 1.0f, 0.3f * std::sin(3.0f * fx) * fy, fy * 2.0f - 1.0f});
        const glm::vec3 normal = glm::normalize(glm::vec3(-0.9f * std::cos(3.0f * fx) * fy, 1.0f, 0.4f * fx - 0.2f));
        normals.insert(normals.end(), {normal.x, normal.y, normal.z, 0.0f});
        uvs.insert(uvs.end(), {fx * 3.0f, 1.0f - fy * 0.5f});
      }
    std::vector<std::uint32_t> triangles;
    for (int y = 0; y + 1 < n; ++y)
      for (int x = 0; x + 1 < n; ++x) {
        const std::uint32_t a = std::uint32_t(y * n + x), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
        triangles.insert(triangles.end(), {a, c, b, b, c, d});
      }
    const std::vector<float> quats = {0, 0, 0, 1, 0, 0.3826834f, 0, 0.9238795f, 0, 0.7071068f, 0, 0.7071068f};
    vertices_ = positions.size() / 3;
    expectedNormals_ = normals;
    expectedQuats_ = quats;

    std::vector<unsigned char> octahedral(vertices_ * 4), quaternions(3 * 8), exponential(vertices_ * 8);
    meshopt_encodeFilterOct(octahedral.data(), vertices_, 4, 8, normals.data());
    meshopt_encodeFilterQuat(quaternions.data(), 3, 8, 12, quats.data());
    meshopt_encodeFilterExp(exponential.data(), vertices_, 8, 15, uvs.data());
    streams_.push_back(attributeStream(bytesOf(positions), 12, "NONE", 12));           // 0 POSITION
    streams_.push_back(attributeStream(octahedral, 4, "OCTAHEDRAL", 4));               // 1 NORMAL
    streams_.push_back(attributeStream(exponential, 8, "EXPONENTIAL", 8));             // 2 TEXCOORD_0
    streams_.push_back(indexStream(triangles, "TRIANGLES", 2, vertices_));             // 3 indices
    std::vector<std::uint32_t> half(triangles.begin(), triangles.begin() + std::ptrdiff_t(triangles.size() / 2));
    streams_.push_back(indexStream(half, "INDICES", 4, vertices_));                    // 4 indices
    streams_.push_back(attributeStream(bytesOf(std::vector<float>{0.0f, 0.5f, 1.0f}), 4, "NONE"));  // 5 key times
    streams_.push_back(attributeStream(quaternions, 8, "QUATERNION"));                 // 6 rotations
    for (Stream& s : streams_) {
      s.plainOffset = plain_.size();
      plain_.insert(plain_.end(), s.plain.begin(), s.plain.end());
      plain_.resize((plain_.size() + 3) & ~std::size_t{3}, 0);
      s.packedOffset = packed_.size();
      packed_.insert(packed_.end(), s.packed.begin(), s.packed.end());
      packed_.resize((packed_.size() + 3) & ~std::size_t{3}, 0);
    }
  }

  // Uncompressed: one buffer of the plain layout. Compressed: buffer 0 holds the
  // meshopt streams, buffer 1 is the fallback (no uri) the views lie in.
  json doc(bool compressed) const {
    json d = {{"asset", {{"version", "2.0"}}},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes", {{{"primitives",
                            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}},
                             {{"attributes", {{"POSITION", 0}}}, {"indices", 4}}}}}}},
              {"animations", {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}},
                               {"samplers", {{{"input", 5}, {"output", 6}}}}}}}};
    auto accessor = [](int view, int type, std::size_t count, const char* shape, bool normalized = false) {
      json a = {{"bufferView", view}, {"componentType", type}, {"count", count}, {"type", shape}};
      if (normalized) a["normalized"] = true;
      return a;
    };
    d["accessors"] = {accessor(0, 5126, vertices_, "VEC3"), accessor(1, 5120, vertices_, "VEC3", true),
                      accessor(2, 5126, vertices_, "VEC2"),  accessor(3, 5123, streams_[3].count, "SCALAR"),
                      accessor(4, 5125, streams_[4].count, "SCALAR"), accessor(5, 5126, 3, "SCALAR"),
                      accessor(6, 5122, 3, "VEC4", true)};
    d["accessors"][5]["min"] = {0.0};
    d["accessors"][5]["max"] = {1.0};
    for (const Stream& s : streams_) {
      json view = {{"buffer", compressed ? 1 : 0}, {"byteOffset", s.plainOffset}, {"byteLength", s.plain.size()}};
      if (s.viewStride) view["byteStride"] = s.viewStride;
      if (compressed) {
        json ext = {{"buffer", 0}, {"byteOffset", s.packedOffset}, {"byteLength", s.packed.size()},
                    {"byteStride", s.stride}, {"count", s.count}, {"mode", s.mode}};
        if (s.filter != "NONE") ext["filter"] = s.filter;
        view["extensions"] = {{"EXT_meshopt_compression", ext}};
      }
      d["bufferViews"].push_back(view);
    }
    if (!compressed) {
      d["buffers"] = {{{"byteLength", plain_.size()}}};
      return d;
    }
    d["extensionsUsed"] = {"EXT_meshopt_compression"};
    d["extensionsRequired"] = {"EXT_meshopt_compression"};
    d["buffers"] = {{{"byteLength", packed_.size()}},
                    {{"byteLength", plain_.size()}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    return d;
  }
  std::vector<unsigned char> glb(bool compressed) const { return glbOf(doc(compressed), compressed ? packed_ : plain_); }
  // The compressed model as .gltf text, its streams in a data: URI.
  std::string gltfText() const {
    json d = doc(true);
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(packed_);
    return d.dump();
  }

  std::vector<Stream> streams_;
  std::vector<unsigned char> plain_, packed_;
  std::size_t vertices_ = 0;
  std::vector<float> expectedNormals_, expectedQuats_;
};

void expectSameModel(const ModelData& a, const ModelData& b) {
  ASSERT_EQ(a.meshes.size(), 1u);
  ASSERT_EQ(b.meshes.size(), 1u);
  ASSERT_EQ(a.meshes[0].primitives.size(), b.meshes[0].primitives.size());
  for (std::size_t p = 0; p < a.meshes[0].primitives.size(); ++p) {
    const PrimitiveData &x = a.meshes[0].primitives[p], &y = b.meshes[0].primitives[p];
    EXPECT_EQ(x.positions, y.positions) << "primitive " << p;
    EXPECT_EQ(x.normals, y.normals) << "primitive " << p;
    EXPECT_EQ(x.uvs, y.uvs) << "primitive " << p;
    EXPECT_EQ(x.indices, y.indices) << "primitive " << p;
  }
  ASSERT_EQ(a.animations.size(), 1u);
  ASSERT_EQ(b.animations.size(), 1u);
  EXPECT_EQ(a.animations[0].channels[0].times, b.animations[0].channels[0].times);
  EXPECT_EQ(a.animations[0].channels[0].values, b.animations[0].channels[0].values);
}

// Decoded through the loader, the compressed model is the uncompressed one to
// the bit, as GLB and as .gltf text (both need the fallback buffer handled).
TEST(Meshopt, DecodesEveryModeAndFilterExactly) {
  const MeshoptModel m;
  auto plain = loadGltfFromMemory(m.glb(false), "plain.glb");
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  auto packed = loadGltfFromMemory(m.glb(true), "packed.glb");
  ASSERT_TRUE(packed.ok()) << packed.error().message;
  expectSameModel(*packed, *plain);
  const std::string text = m.gltfText();
  auto fromText = loadGltfFromMemory(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), "packed.gltf");
  ASSERT_TRUE(fromText.ok()) << fromText.error().message;
  expectSameModel(*fromText, *plain);

  // The filters really ran: octahedral normals within 8-bit precision of the
  // unit vectors encoded, quaternions within 12-bit precision.
  const PrimitiveData& prim = packed->meshes[0].primitives[0];
  ASSERT_EQ(prim.normals.size(), m.vertices_);
  for (std::size_t i = 0; i < m.vertices_; ++i) {
    const glm::vec3 expected(m.expectedNormals_[4 * i], m.expectedNormals_[4 * i + 1], m.expectedNormals_[4 * i + 2]);
    ASSERT_LT(glm::distance(glm::normalize(prim.normals[i]), expected), 0.03f) << "vertex " << i;
  }
  EXPECT_EQ(prim.indices.size(), 8u * 8u * 6u);
  EXPECT_EQ(packed->meshes[0].primitives[1].indices.size(), 8u * 8u * 3u);
  const auto& rotations = packed->animations[0].channels[0].values;
  ASSERT_EQ(rotations.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(rotations[k][c], m.expectedQuats_[4 * k + std::size_t(c)], 2e-3f) << k;
}

TEST(Meshopt, TruncatedOrCorruptStreamsNameTheBufferView) {
  const MeshoptModel m;
  auto load = [&](const std::function<void(json&)>& edit) {
    json d = m.doc(true);
    edit(d);
    return loadGltfFromMemory(glbOf(d, m.packed_), "packed.glb");
  };
  auto expect = [](const Result<ModelData>& model, const std::string& needle) {
    ASSERT_FALSE(model.ok());
    EXPECT_EQ(model.error().message.rfind("packed.glb: ", 0), 0u) << model.error().message;
    EXPECT_NE(model.error().message.find(needle), std::string::npos) << model.error().message;
  };
  const json base = m.doc(true);
  for (int view : {0, 1, 3, 4, 6}) {
    const std::size_t length = base["bufferViews"][std::size_t(view)]["extensions"]["EXT_meshopt_compression"]["byteLength"];
    expect(load([&](json& d) { d["bufferViews"][std::size_t(view)]["extensions"]["EXT_meshopt_compression"]["byteLength"] = length / 2; }),
           "bufferView " + std::to_string(view) + ": EXT_meshopt_compression: decode failed: meshopt error");
  }
  expect(load([](json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6; }),
         "bufferView 0: EXT_meshopt_compression: ATTRIBUTES need a byteStride that is a multiple of 4 in [4, 256], not 6");
  expect(load([](json& d) { d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["count"] = 4; }),
         "bufferView 3: EXT_meshopt_compression: TRIANGLES count 4 is not a multiple of 3");
  expect(load([](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "SPHERICAL"; }),
         "bufferView 1: EXT_meshopt_compression: unknown filter \"SPHERICAL\"");
  expect(load([](json& d) { d["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 1 << 30; }),
         "bufferView 2: EXT_meshopt_compression: bytes [1073741824, ");
  // 2^26 positions of 12 bytes (768 MiB) from 300 bytes: refused before allocating.
  expect(load([](json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 26; }),
         "bufferView 0: EXT_meshopt_compression: decodes to 805306368 bytes, more than the 536870912");
  // A plain view into the fallback buffer has no data to read.
  expect(load([](json& d) { d["bufferViews"][5].erase("extensions"); }), "bufferView 5: bytes [");
  // The stream's bytes overwritten: the decoder must refuse them, not read past
  // them, or decode garbage that the loader's own checks then name (0xFF bytes
  // make NaN positions).
  int refused = 0;
  for (std::size_t at = 0; at < m.streams_[0].packed.size(); at += 16) {
    std::vector<unsigned char> broken = m.packed_;
    std::fill_n(broken.begin() + std::ptrdiff_t(at), std::min<std::size_t>(16, m.streams_[0].packed.size() - at), 0xFF);
    auto model = loadGltfFromMemory(glbOf(m.doc(true), broken), "packed.glb");
    if (!model.ok()) {
      ++refused;
      const std::string& message = model.error().message;
      EXPECT_TRUE(message.rfind("packed.glb: bufferView 0: EXT_meshopt_compression: decode failed", 0) == 0 ||
                  message.rfind("packed.glb: mesh 0 primitive 0 POSITION: element ", 0) == 0)
          << message;
    }
  }
  EXPECT_GT(refused, 0);
}

// gltfpack's output of the project's robot (tests/data/meshopt): every mode and
// filter as a real encoder writes them, the fallback buffer without a uri, and
// KHR_mesh_quantization's integer positions undone by the inverse bind matrices.
// In the bind pose it covers the robot's box (gltfpack -si 0.25 dropped three
// quarters of the triangles, which moves the box by a few percent at most).
TEST(Meshopt, GltfpackRobotLoadsAndMatchesTheOriginal) {
  const std::string packedPath = std::string(ENGINE_SOURCE_DIR) + "/tests/data/meshopt/character_meshopt.glb";
  auto packed = loadGltf(packedPath);
  ASSERT_TRUE(packed.ok()) << packed.error().message;
  auto original = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf");
  ASSERT_TRUE(original.ok()) << original.error().message;
  for (const std::string& w : packed->warnings) EXPECT_EQ(w.find("meshopt"), std::string::npos) << w;
  ASSERT_EQ(packed->skins.size(), 1u);
  EXPECT_EQ(packed->skins[0].joints.size(), original->skins[0].joints.size());
  EXPECT_EQ(packed->animations.size(), original->animations.size());

  auto bindPoseBox = [](const ModelData& model, glm::vec3& lo, glm::vec3& hi) {
    std::vector<glm::mat4> world(model.nodes.size(), glm::mat4(1.0f));
    forEachNode(model, [&](const NodeData& node, const glm::mat4& w) { world[std::size_t(&node - model.nodes.data())] = w; });
    const SkinData& skin = model.skins[0];
    const PrimitiveData& prim = model.meshes[0].primitives[0];
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    for (std::size_t v = 0; v < prim.positions.size(); ++v) {
      glm::vec3 p(0.0f);
      for (int k = 0; k < prim.influences; ++k) {
        const std::size_t at = v * std::size_t(prim.influences) + std::size_t(k);
        const std::size_t joint = prim.joints[at];
        p += prim.weights[at] * glm::vec3(world[std::size_t(skin.joints[joint])] * skin.inverseBinds[joint] *
                                          glm::vec4(prim.positions[v], 1.0f));
      }
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  };
  glm::vec3 lo, hi, refLo, refHi;
  bindPoseBox(*packed, lo, hi);
  bindPoseBox(*original, refLo, refHi);
  const float size = glm::length(refHi - refLo);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(lo[c], refLo[c], 0.03f * size) << "axis " << c;
    EXPECT_NEAR(hi[c], refHi[c], 0.03f * size) << "axis " << c;
  }
  for (const glm::vec3& n : packed->meshes[0].primitives[0].normals) ASSERT_NEAR(glm::length(n), 1.0f, 0.02f);
  for (const AnimationData& a : packed->animations)
    for (const ChannelData& ch : a.channels) {
      if (ch.path != AnimPath::Rotation) continue;
      for (const glm::vec4& q : ch.values) ASSERT_NEAR(glm::length(q), 1.0f, 2e-3f);
    }
}

}  // namespace
}  // namespace engine
