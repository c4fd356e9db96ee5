// GPU skinning (shaders/common/skinning.glsl) against the CPU SkinningJob: the
// skinned positions are captured with transform feedback and must agree to 1e-5 of
// the model's size, for linear blend and dual quaternions, 4 and 8 influences.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/capture.h"
#include "../support/gl_test.h"
#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "gl/resources.h"
#include "render/model_renderer.h"
#include "render/render_target.h"

using namespace engine;
using engine::test::CaptureInputs;
using engine::test::captureVarying;
using engine::test::GlTest;
using engine::test::largestRelativeError;

namespace {

// Float GPU and CPU sum the same products in a different order: a few ulps of the
// largest coordinate, far below 1e-5 of the size.
constexpr double kRelativeTolerance = 1e-5;

// The palettes of one skin in one pose (tests/support/capture.h).
using Posed = test::Palettes;

Posed poseSkin(const AnimatedModel& animated, int clip, double time, int skin) {
  return test::palettesOf(animated.skins[size_t(skin)], test::poseModel(animated, clip, time));
}

std::vector<glm::vec3> cpuSkin(const PrimitiveData& prim, const Posed& posed, SkinMode mode) {
  std::vector<glm::vec3> out(prim.positions.size());
  SkinningJob job;
  job.method = mode == SkinMode::DualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
  job.influences = prim.influences;
  job.positions = prim.positions;
  job.joints = prim.joints;
  job.weights = prim.weights;
  job.palette = posed.palette;
  job.dualQuats = posed.dualQuats;
  job.outPositions = out;
  EXPECT_TRUE(job.run());
  return out;
}

CaptureInputs inputsOf(const Posed& posed) { return {posed.palette, posed.dualQuats, {}, glm::mat4(1.0f)}; }

std::vector<glm::vec3> gpuSkin(ShaderVariants& variants, const GpuPrimitive& prim, const Posed& posed,
                               SkinMode mode) {
  return captureVarying<glm::vec3>(variants, prim, inputsOf(posed), {prim.influences, mode}, "v_position");
}

// Every skinned primitive of every node, at one time, both skinning methods.
void compareModel(const ModelData& model, int clip, double time) {
  auto animated = buildAnimatedModel(model);
  ASSERT_TRUE(animated.ok()) << animated.error().message;
  auto gpu = GpuModel::upload(model);
  ASSERT_TRUE(gpu.ok()) << gpu.error().message;
  ShaderVariants variants(test::shaderDir());
  int compared = 0;
  for (const NodeData& node : model.nodes) {
    if (node.mesh < 0 || node.skin < 0) continue;
    const Posed posed = poseSkin(*animated, clip, time, node.skin);
    const auto& prims = model.meshes[size_t(node.mesh)].primitives;
    for (size_t p = 0; p < prims.size(); ++p) {
      if (prims[p].influences == 0) continue;
      for (SkinMode mode : {SkinMode::Linear, SkinMode::DualQuat}) {
        const auto cpu = cpuSkin(prims[p], posed, mode);
        const auto gpuOut = gpuSkin(variants, gpu->meshes()[size_t(node.mesh)][p], posed, mode);
        ASSERT_EQ(cpu.size(), gpuOut.size());
        const double error = largestRelativeError(gpuOut, cpu);
        std::printf("%s %s influences %d: GPU vs CPU %.3g of the size\n", model.path.c_str(),
                    mode == SkinMode::DualQuat ? "DQS" : "LBS", prims[p].influences, error);
        EXPECT_LE(error, kRelativeTolerance) << (mode == SkinMode::DualQuat ? "DQS" : "LBS")
                                             << " influences " << prims[p].influences;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 0) << "no skinned primitive was compared";
}

// A bent chain of 8 joints with every vertex weighted over all 8.
ModelData eightInfluenceModel() {
  ModelData model;
  model.path = "eight.gltf";
  for (int j = 0; j < 8; ++j) {
    NodeData node;
    node.parent = j - 1;
    node.translation = j == 0 ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.5f, 0.0f);
    node.rotation = glm::angleAxis(0.2f * float(j), glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)));
    if (j < 7) node.children.push_back(j + 1);
    model.nodes.push_back(node);
  }
  NodeData meshNode;
  meshNode.mesh = 0;
  meshNode.skin = 0;
  model.nodes.push_back(meshNode);
  model.sceneRoots = {0, 8};
  SkinData skin;
  for (int j = 0; j < 8; ++j) {
    skin.joints.push_back(j);
    skin.inverseBinds.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.5f * float(j), 0.0f)));
  }
  model.skins.push_back(skin);
  PrimitiveData prim;
  prim.influences = 8;
  for (int v = 0; v < 64; ++v) {
    prim.positions.push_back({0.1f * float(v % 4), 0.06f * float(v), 0.05f * float(v % 3)});
    float total = 0.0f;
    std::vector<float> w(8);
    for (int k = 0; k < 8; ++k) total += (w[size_t(k)] = 1.0f / (1.0f + float(std::abs(v / 8 - k))));
    for (int k = 0; k < 8; ++k) {
      prim.joints.push_back(std::uint16_t(7 - k));
      prim.weights.push_back(w[size_t(k)] / total);
    }
  }
  MeshData mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  return model;
}

// One mesh drawn twice, by two nodes with two different skins over two joint chains
// (the RecursiveSkeletons case): each instance follows its own skeleton.
ModelData twoSkinsOneMesh() {
  ModelData model = eightInfluenceModel();
  const int chainB = int(model.nodes.size());
  for (int j = 0; j < 8; ++j) {
    NodeData node = model.nodes[size_t(j)];
    node.parent = j == 0 ? -1 : chainB + j - 1;
    node.children.clear();
    if (j < 7) node.children.push_back(chainB + j + 1);
    node.translation += j == 0 ? glm::vec3(2.0f, 0.0f, 0.0f) : glm::vec3(0.0f);
    node.rotation = glm::angleAxis(-0.3f * float(j), glm::vec3(1.0f, 0.0f, 0.0f));
    model.nodes.push_back(node);
  }
  SkinData skin = model.skins[0];
  for (int& joint : skin.joints) joint += chainB;
  model.skins.push_back(skin);
  NodeData second;
  second.mesh = 0;
  second.skin = 1;
  model.nodes.push_back(second);
  model.sceneRoots = {0, 8, chainB, int(model.nodes.size()) - 1};
  return model;
}

std::string conformanceDir() {
  if (const char* env = std::getenv("CONFORMANCE_DIR")) return env;
  return std::string(ENGINE_SOURCE_DIR) + "/../shared/conformance";
}

}  // namespace

class GpuSkinning : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuSkinning);

TEST_P(GpuSkinning, EightInfluencesMatchCpu) { compareModel(eightInfluenceModel(), -1, 0.0); }

TEST_P(GpuSkinning, TwoSkinsOnOneMeshEachFollowTheirSkeleton) {
  const ModelData model = twoSkinsOneMesh();
  compareModel(model, -1, 0.0);
  auto pose = dumpPose(model, -1, 0.0);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  const auto& meshes = (*pose)["meshes"];
  ASSERT_EQ(meshes.size(), 2u);
  EXPECT_NE(meshes[0]["positions"], meshes[1]["positions"]) << "both instances took the same skin";
}

TEST_P(GpuSkinning, CesiumManMatchesCpu) {
  const std::string path = conformanceDir() + "/assets/CesiumMan/glTF-Binary/CesiumMan.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (../shared/conformance absent)";
  auto model = loadGltf(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  for (double t : {0.0, 0.5005, 1.013}) compareModel(*model, 0, t);
}

TEST_P(GpuSkinning, ShippedCharacterMatchesCpu) {
  const std::string path = std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not generated yet";
  auto model = loadGltf(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  for (int clip = 0; clip < int(model->animations.size()); ++clip) compareModel(*model, clip, 0.37);
}

// Normal-mapped skinned meshes skin the tangent with the same blend as the
// position: a direction d is carried exactly like skin(p + d) - skin(p) (LBS is
// linear in p; the blended dual quaternion does not depend on p). The tangent is
// captured from the NORMAL_MAP variant and compared with that difference of two
// CPU-skinned positions.
TEST_P(GpuSkinning, TangentsAreSkinnedLikePositions) {
  ModelData model = eightInfluenceModel();
  PrimitiveData& prim = model.meshes[0].primitives[0];
  std::vector<glm::vec3> shifted;
  for (size_t v = 0; v < prim.positions.size(); ++v) {
    const float a = 0.7f * float(v);
    const glm::vec3 t = glm::normalize(glm::vec3(std::cos(a), 0.3f, std::sin(a)));
    prim.tangents.emplace_back(t, v % 2 ? -1.0f : 1.0f);
    shifted.push_back(prim.positions[v] + t);
  }
  PrimitiveData shiftedPrim = prim;
  shiftedPrim.positions = shifted;
  auto animated = buildAnimatedModel(model);
  ASSERT_TRUE(animated.ok()) << animated.error().message;
  auto gpu = GpuModel::upload(model);
  ASSERT_TRUE(gpu.ok()) << gpu.error().message;
  ShaderVariants variants(test::shaderDir());
  const Posed posed = poseSkin(*animated, -1, 0.0, 0);
  const GpuPrimitive& gpuPrim = gpu->meshes()[0][0];
  ASSERT_TRUE(gpuPrim.hasTangents);
  for (SkinMode mode : {SkinMode::Linear, SkinMode::DualQuat}) {
    SCOPED_TRACE(mode == SkinMode::DualQuat ? "DQS" : "LBS");
    ShaderVariant variant{8, mode};
    variant.normalMap = true;
    const auto tangents = captureVarying<glm::vec4>(variants, gpuPrim, inputsOf(posed), variant, "v_tangent");
    ASSERT_EQ(tangents.size(), prim.positions.size());
    const auto base = cpuSkin(prim, posed, mode), moved = cpuSkin(shiftedPrim, posed, mode);
    double worst = 0.0;
    for (size_t v = 0; v < tangents.size(); ++v) {
      worst = std::max(worst, double(glm::length(glm::vec3(tangents[v]) - (moved[v] - base[v]))));
      EXPECT_EQ(tangents[v].w, prim.tangents[v].w) << v;  // handedness passes through
    }
    // The CPU difference of two skinned positions carries their rounding (a few
    // ulps of coordinates up to ~4 m): 1e-5 of the unit tangent.
    std::printf("skinned tangent, GPU vs CPU: largest error %.3g\n", worst);
    EXPECT_LE(worst, 1e-5);
  }
}
