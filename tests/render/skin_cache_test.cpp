// The skin cache (render/skin_cache.h, shaders/skin.comp) against the CPU path the
// pose dump and the tracers use (posePrimitive: MorphJob, then SkinningJob): every
// deforming primitive's cached positions must agree to 1e-5 of the model's size,
// LBS and DQS, skinned and morphed, on the shipped character, CesiumMan, Khronos's
// morph models and the skinned, morphed MorphInterpolation strip. And a scene drawn
// with --skinning compute must look exactly as with vertex skinning, on both
// backends, through every pass (sun maps, the point light's cube, the main view).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "../support/capture.h"
#include "../support/gl_test.h"
#include "anim/model_builder.h"
#include "asset/gltf_loader.h"
#include "asset/scene_file.h"
#include "render/character.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"
#include "render/skin_cache.h"

using namespace engine;
using engine::test::GlTest;
using engine::test::largestRelativeError;

namespace {

// The GPU and the CPU run the same products; their sums differ by a few ulps of
// the largest coordinate (FMA contraction), far below 1e-5 of the size.
constexpr double kRelativeTolerance = 1e-5;
// Against the vertex shader itself: a few ulps (see compareInstance).
constexpr double kVertexShaderUlps = 8.0;

struct Deformed {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
};

// skin.comp's output: three vec4 per vertex of `prim`'s buffers (position, normal,
// tangent), as one per vertex of its PrimitiveData.
Deformed readBack(const gl::Buffer& buffer, const GpuPrimitive& prim) {
  std::vector<glm::vec4> raw(3 * size_t(prim.vertexCount));
  glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(raw.size() * sizeof(glm::vec4)), raw.data());
  std::vector<glm::vec3> positions, normals;
  for (size_t v = 0; v < size_t(prim.vertexCount); ++v) {
    positions.emplace_back(raw[3 * v]);
    normals.emplace_back(raw[3 * v + 1]);
  }
  return {test::perSourceVertex(prim, positions), test::perSourceVertex(prim, normals)};
}

double largestAngleError(const std::vector<glm::vec3>& gpu, const std::vector<glm::vec3>& cpu) {
  double worst = 0.0;
  for (size_t v = 0; v < gpu.size() && v < cpu.size(); ++v)
    worst = std::max(worst, double(glm::length(glm::normalize(gpu[v]) - cpu[v])));
  return worst;
}

// The largest |a - b| in units of the largest coordinate of `b` (float ulps of it:
// 2^-23 of its magnitude).
double largestUlps(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double worst = 0.0, magnitude = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    magnitude = std::max({magnitude, double(std::abs(b[i].x)), double(std::abs(b[i].y)), double(std::abs(b[i].z))});
    worst = std::max(worst, double(glm::length(a[i] - b[i])));
  }
  return worst / std::max(1e-30, magnitude * 0x1p-23);
}

// The same primitive deformed by the vertex shader (scene.vert's variant, captured
// with transform feedback), which every pass ran before the cache.
std::vector<glm::vec3> vertexShaderPositions(ShaderVariants& variants, const CharacterInstance& instance,
                                             SkinMode mode, size_t n, size_t p) {
  const ModelData& model = instance.asset().model;
  const AnimatedModel& animated = instance.asset().animated;
  const NodeData& node = model.nodes[n];
  const PrimitiveData& prim = model.meshes[size_t(node.mesh)].primitives[p];
  const bool skinned = node.skin >= 0 && prim.influences > 0;
  test::ModelPose pose{{instance.models().begin(), instance.models().end()},
                       {instance.morphWeights().begin(), instance.morphWeights().end()}};
  const test::Palettes palettes = skinned ? test::palettesOf(animated.skins[size_t(node.skin)], pose) : test::Palettes{};
  const test::CaptureInputs inputs{palettes.palette, palettes.dualQuats, animated.morphs.of(pose.weights, int(n)),
                                   glm::mat4(1.0f)};
  return test::captureVarying<glm::vec3>(variants, instance.asset().gpu.meshes()[size_t(node.mesh)][p], inputs,
                                         primitiveVariant(model, node, prim, mode, false), "v_position");
}

// Every cached (node, primitive) of one posed instance against posePrimitive and
// against the vertex shader. Returns how many were compared.
int compareInstance(ShaderVariants& variants, const CharacterInstance& instance, SkinMode mode) {
  const ModelData& model = instance.asset().model;
  const AnimatedModel& animated = instance.asset().animated;
  const SkinCache* cache = instance.skinCache();
  EXPECT_NE(cache, nullptr);
  if (!cache) return 0;
  int compared = 0;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = model.meshes[size_t(node.mesh)].primitives;
    for (size_t p = 0; p < prims.size(); ++p) {
      const PrimitiveData& prim = prims[p];
      const gl::Buffer* output = cache->output(int(n), int(p));
      EXPECT_EQ(output != nullptr, deforms(node, prim)) << "node " << n << " primitive " << p;
      if (!output) continue;
      const bool skinned = node.skin >= 0 && prim.influences > 0 && mode != SkinMode::None;
      // Unskinned, the cache holds the morphed mesh in its own space (the draw
      // places it by its node): the CPU's world is the identity.
      const PrimitivePose pose{animated.morphs.of(instance.morphWeights(), int(n)),
                               skinned ? &animated.skins[size_t(node.skin)] : nullptr, instance.models(),
                               glm::mat4(1.0f), mode == SkinMode::DualQuat ? SkinningMethod::DualQuat
                                                                           : SkinningMethod::Linear};
      std::vector<glm::vec3> positions(prim.positions.size()), normals(prim.normals.size());
      EXPECT_TRUE(posePrimitive(prim, pose, positions, normals));
      const Deformed gpu = readBack(*output, instance.asset().gpu.meshes()[size_t(node.mesh)][p]);
      const double error = largestRelativeError(gpu.positions, positions);
      std::printf("%s node %zu primitive %zu %s: skin cache vs CPU %.3g of the size\n", model.path.c_str(), n, p,
                  mode == SkinMode::DualQuat ? "DQS" : "LBS", error);
      EXPECT_LE(error, kRelativeTolerance) << model.path << " node " << n << " primitive " << p;
      // The vertex shader runs the same functions, but may contract its sums into
      // FMAs differently (it also multiplies by u_model in the same expression).
      const double ulps = largestUlps(gpu.positions, vertexShaderPositions(variants, instance, mode, n, p));
      std::printf("  against the vertex shader: %.2f ulps of the largest coordinate\n", ulps);
      EXPECT_LE(ulps, kVertexShaderUlps) << model.path << " node " << n << " primitive " << p;
      // LBS normals take the blended matrix on the GPU, its cofactor on the CPU
      // (tests/render/morph_gl_test.cpp says why): compared for DQS and rigid only.
      if (!normals.empty() && (mode == SkinMode::DualQuat || !skinned)) {
        EXPECT_LE(largestAngleError(gpu.normals, normals), 1e-5) << "normals, node " << n;
      }
      ++compared;
    }
  }
  return compared;
}

// The model played at each time in both skinning modes.
void compareModel(ModelData model, int clip, std::initializer_list<double> times) {
  auto asset = CharacterAsset::create(std::move(model));
  ASSERT_TRUE(asset.ok()) << asset.error().message;
  SkinPrograms programs(test::shaderDir());
  ShaderVariants variants(test::shaderDir());
  CharacterInstance instance(*asset);
  instance.useSkinCache(&programs);
  int compared = 0;
  for (double t : times) {
    instance.play(clip, LoopMode::Repeat, t);
    ASSERT_TRUE(instance.evaluate().ok());
    for (SkinMode mode : {SkinMode::Linear, SkinMode::DualQuat}) {
      ASSERT_TRUE(instance.prepare(mode).ok());
      compared += compareInstance(variants, instance, mode);
    }
  }
  EXPECT_GT(compared, 0) << "nothing deforms";
}

Result<ModelData> loadShared(const std::string& relative) {
  const std::string path = std::string(ENGINE_SOURCE_DIR) + "/../shared/" + relative;
  if (!std::filesystem::exists(path)) return makeError(path + " not found");
  return loadGltf(path);
}

}  // namespace

class SkinCacheTest : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(SkinCacheTest);

TEST_P(SkinCacheTest, ShippedCharacterMatchesCpu) {
  auto model = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  const int clips = int(model->animations.size());
  for (int clip = 0; clip < clips; ++clip) compareModel(*model, clip, {0.0, 0.37, 1.9});
}

TEST_P(SkinCacheTest, CesiumManMatchesCpu) {
  auto model = loadShared("conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb");
  if (!model) GTEST_SKIP() << model.error().message;
  compareModel(*model, 0, {0.0, 0.5005, 1.013});
}

// Morphed and skinned in glTF's order, and morphed only.
TEST_P(SkinCacheTest, MorphedModelsMatchCpu) {
  auto strip = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/tests/conformance/morph_poses/MorphInterpolation.gltf");
  ASSERT_TRUE(strip.ok()) << strip.error().message;
  compareModel(*strip, 0, {0.0, 0.31, 1.27});
  for (const char* path : {"gltf-samples/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
                           "gltf-samples/MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb"}) {
    auto model = loadShared(path);
    if (!model) {
      std::printf("skipped: %s\n", model.error().message.c_str());
      continue;
    }
    compareModel(*model, model->animations.empty() ? -1 : 0, {0.0, 0.7});
  }
}

// A model that does not deform gets an empty cache, and is drawn as before.
TEST_P(SkinCacheTest, StaticModelsHaveNoEntries) {
  ModelData model;
  model.path = "static.gltf";
  PrimitiveData prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  MeshData mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  NodeData node;
  node.mesh = 0;
  model.nodes.push_back(node);
  model.sceneRoots = {0};
  auto gpu = GpuModel::upload(model);
  ASSERT_TRUE(gpu.ok());
  const SkinCache cache = SkinCache::create(model, *gpu);
  EXPECT_EQ(cache.entries(), 0);
  EXPECT_EQ(cache.vertexArray(0, 0), nullptr);
}

namespace {

// Four robots (LBS and DQS, walking, waving) under the sun, and the morphing
// strip under a shadowing point light: every pass that draws characters.
constexpr const char* kScene = R"({
  "camera": {"position": [0, 1.6, 5.5], "direction": [0, -0.15, -1], "fovy": 55},
  "lights": [
    {"type": "sun", "direction": [-0.55, 0.7, -0.25], "intensity": 2.4, "shadows": true},
    {"type": "point", "position": [1.5, 2.5, 2.0], "intensity": 6, "shadows": true}
  ],
  "materials": {"ground": {"color": [0.6, 0.6, 0.55]}},
  "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "ground"}],
  "models": [
    {"path": "../models/character.gltf", "position": [0, 0, 0], "clip": "Walk"},
    {"path": "../models/character.gltf", "position": [-1.6, 0, 0.8], "clip": "Wave", "skinning": "dqs"},
    {"path": "../models/character.gltf", "position": [1.5, 0, -0.4], "clip": "Idle", "start": 0.5},
    {"path": "../../tests/conformance/morph_poses/MorphInterpolation.gltf", "position": [0.6, 0.2, 1.5],
     "clip": 0}
  ],
  "sky": {"enabled": true}
})";

Image renderAt(const SceneDesc& scene, Skinning skinning, double time) {
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.skinningOverride = skinning;
  auto renderer = SceneRenderer::create(scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  EXPECT_TRUE((*renderer)->update(time).ok());
  auto target = RenderTarget::create(192, 128, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  const Status status = (*renderer)->render((*renderer)->initialCamera(), 192, 128);
  EXPECT_TRUE(status.ok()) << status.error().message;
  if (skinning == Skinning::Compute) {
    EXPECT_GT((*renderer)->stats().verticesDeformed, 0);
  }
  return target->readPixels();
}

}  // namespace

// The cache's positions are those the vertex shaders compute: skin.comp runs the
// same functions (common/skinning.glsl, common/morph.glsl) in the same order, so
// on this GL every pixel is identical. A driver that contracts the sums into
// FMAs differently in a compute and a vertex stage could move an edge pixel; this
// test would then show by how much, and the bound would be set from that.
TEST_P(SkinCacheTest, ComputeSkinningDrawsTheSameImageAsVertexSkinning) {
  auto scene = parseScene(kScene, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/skin_cache_test.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  for (double time : {0.0, 0.9}) {
    const Image vertex = renderAt(*scene, Skinning::Vertex, time);
    const Image compute = renderAt(*scene, Skinning::Compute, time);
    ASSERT_EQ(vertex.pixels.size(), compute.pixels.size());
    size_t differing = 0;
    for (size_t i = 0; i < vertex.pixels.size(); ++i) differing += vertex.pixels[i] != compute.pixels[i];
    EXPECT_EQ(differing, 0u) << "at t = " << time;
    // And the scene moved between the two times (the test sees animation at all).
    if (time > 0.0) {
      const Image first = renderAt(*scene, Skinning::Compute, 0.0);
      size_t moved = 0;
      for (size_t i = 0; i < first.pixels.size(); ++i) moved += first.pixels[i] != compute.pixels[i];
      EXPECT_GT(moved, 100u);
    }
  }
}
