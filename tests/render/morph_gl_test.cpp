// GPU morph targets (shaders/common/morph.glsl, before skinning) against the CPU
// path that the pose dump and the ray tracer use (posePrimitive: MorphJob, then
// SkinningJob or the node's matrix). Positions, normals and tangents are captured
// with transform feedback and must agree to 1e-5 of the model's size: on Khronos's
// AnimatedMorphCube and MorphPrimitivesTest (skipped when ../shared is absent), on
// the repository's MorphInterpolation.gltf (a skinned, morphed strip) and on a
// built model with 48 targets, rigid and skinned (LBS and DQS), colour and depth
// variants. A model drawn through CharacterInstance gets the "+morph" variant, and
// its culling bounds hold every morphed pose.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/capture.h"
#include "../support/gl_test.h"
#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "render/character.h"
#include "render/model_renderer.h"

using namespace engine;
using engine::test::CaptureInputs;
using engine::test::captureVarying;
using engine::test::GlTest;
using engine::test::largestRelativeError;
using engine::test::ModelPose;
using engine::test::Palettes;
using engine::test::palettesOf;
using engine::test::poseModel;

namespace {

// GPU and CPU add the same products in the same order; FMA contraction and the
// skinning blend differ by a few ulps of the largest coordinate.
constexpr double kRelativeTolerance = 1e-5;

double largestAngleError(const std::vector<glm::vec3>& gpu, const std::vector<glm::vec3>& cpu) {
  double worst = 0.0;
  for (size_t v = 0; v < gpu.size() && v < cpu.size(); ++v) {
    const float len = glm::length(gpu[v]);
    const glm::vec3 n = len > 0.0f ? gpu[v] / len : gpu[v];
    worst = std::max(worst, double(glm::length(n - cpu[v])));
  }
  return worst;
}

struct Counts {
  int positions = 0;
  int normals = 0;
};

// One (node, primitive) instance: the GPU capture against posePrimitive, for the
// colour and the depth-only variant (and both skinning methods when skinned).
void compareInstance(ShaderVariants& variants, const ModelData& model, const AnimatedModel& animated,
                     const GpuModel& gpu, const ModelPose& pose, size_t n, size_t p, Counts& counts) {
  const NodeData& node = model.nodes[n];
  const PrimitiveData& prim = model.meshes[size_t(node.mesh)].primitives[p];
  const GpuPrimitive& gpuPrim = gpu.meshes()[size_t(node.mesh)][p];
  const bool skinned = node.skin >= 0 && prim.influences > 0;
  const std::span<const float> weights = animated.morphs.of(pose.weights, int(n));
  const glm::mat4 world = pose.models[size_t(animated.skeleton.jointOfRaw(int(n)))];
  const Palettes palettes = skinned ? palettesOf(animated.skins[size_t(node.skin)], pose) : Palettes{};
  const std::vector<SkinMode> modes =
      skinned ? std::vector<SkinMode>{SkinMode::Linear, SkinMode::DualQuat} : std::vector<SkinMode>{SkinMode::None};
  for (SkinMode mode : modes) {
    const SkinningMethod method = mode == SkinMode::DualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
    std::vector<glm::vec3> positions(prim.positions.size()), normals(prim.normals.size());
    const PrimitivePose cpuPose{weights, skinned ? &animated.skins[size_t(node.skin)] : nullptr, pose.models, world,
                                method};
    ASSERT_TRUE(posePrimitive(prim, cpuPose, positions, normals));
    const CaptureInputs inputs{palettes.palette, palettes.dualQuats, weights, skinned ? glm::mat4(1.0f) : world};
    for (bool depthOnly : {false, true}) {
      ShaderVariant variant = primitiveVariant(model, node, prim, mode, depthOnly);
      ASSERT_TRUE(variant.morph) << variant.describe();
      SCOPED_TRACE(model.path + " node " + std::to_string(n) + " primitive " + std::to_string(p) + " " +
                   variant.describe());
      const double error = largestRelativeError(captureVarying<glm::vec3>(variants, gpuPrim, inputs, variant, "v_position"), positions);
      std::printf("%s node %zu primitive %zu %s: GPU vs CPU %.3g of the size\n", model.path.c_str(), n, p,
                  variant.describe().c_str(), error);
      EXPECT_LE(error, kRelativeTolerance);
      ++counts.positions;
      // LBS on the GPU takes the blended matrix itself for normals (skinning.glsl),
      // the CPU its cofactor: they agree only for rigid blends, so LBS normals are
      // not compared. Rigid and DQS normals are exact rotations of the morphed one.
      if (normals.empty() || mode == SkinMode::Linear || depthOnly) continue;
      const double angle = largestAngleError(captureVarying<glm::vec3>(variants, gpuPrim, inputs, variant, "v_normal"), normals);
      EXPECT_LE(angle, 1e-5) << "normals";
      ++counts.normals;
    }
  }
}

// Every morphing (node, primitive) instance of `model` at one time.
Counts compareModel(const ModelData& model, int clip, double time) {
  auto animated = buildAnimatedModel(model);
  EXPECT_TRUE(animated.ok()) << animated.error().message;
  auto gpu = GpuModel::upload(model);
  EXPECT_TRUE(gpu.ok()) << gpu.error().message;
  Counts counts;
  if (!animated || !gpu) return counts;
  ShaderVariants variants(test::shaderDir());
  const ModelPose pose = poseModel(*animated, clip, time);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    if (model.nodes[n].mesh < 0) continue;
    const auto& prims = model.meshes[size_t(model.nodes[n].mesh)].primitives;
    for (size_t p = 0; p < prims.size(); ++p)
      if (prims[p].morphTargets > 0) compareInstance(variants, model, *animated, *gpu, pose, n, p, counts);
  }
  return counts;
}

// A chain of 4 joints skinning a 60-vertex ribbon (4 influences), with normals and
// tangents, and 48 targets moving all three; node 5 draws it skinned, node 4
// rigidly under a non-uniform scale. Some weights are zero, some negative.
ModelData manyTargetModel() {
  constexpr int kTargets = 48, kVertices = 60;
  ModelData model;
  model.path = "many_targets.gltf";
  for (int j = 0; j < 4; ++j) {
    NodeData joint;
    joint.parent = j - 1;
    joint.translation = j == 0 ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.6f, 0.0f);
    joint.rotation = glm::angleAxis(0.35f * float(j), glm::normalize(glm::vec3(0.2f, 0.4f, 1.0f)));
    if (j < 3) joint.children.push_back(j + 1);
    model.nodes.push_back(joint);
  }
  PrimitiveData prim;
  prim.influences = 4;
  prim.morphTargets = kTargets;
  for (int v = 0; v < kVertices; ++v) {
    const float y = 0.04f * float(v);
    prim.positions.push_back({0.2f * float(v % 2), y, 0.05f * float(v % 3)});
    prim.normals.push_back(glm::normalize(glm::vec3(0.1f * float(v % 5), 0.3f, 1.0f)));
    prim.tangents.emplace_back(glm::normalize(glm::vec3(1.0f, 0.1f * float(v % 4), 0.0f)), v % 2 ? 1.0f : -1.0f);
    float total = 0.0f;
    float w[4];
    for (int k = 0; k < 4; ++k) total += (w[k] = 1.0f / (1.0f + std::abs(y / 0.6f - float(k))));
    for (int k = 0; k < 4; ++k) {
      prim.joints.push_back(std::uint16_t(k));
      prim.weights.push_back(w[k] / total);
    }
  }
  for (int t = 0; t < kTargets; ++t)
    for (int v = 0; v < kVertices; ++v) {
      const float a = 0.37f * float(t) + 0.11f * float(v);
      prim.morphPositions.push_back(0.05f * glm::vec3(std::sin(a), std::cos(1.3f * a), std::sin(0.7f * a)));
      prim.morphNormals.push_back(0.2f * glm::vec3(std::cos(a), std::sin(0.5f * a), 0.0f));
      prim.morphTangents.push_back(0.1f * glm::vec3(0.0f, std::cos(0.9f * a), std::sin(a)));
    }
  MeshData mesh;
  mesh.primitives.push_back(prim);
  for (int t = 0; t < kTargets; ++t) mesh.morphWeights.push_back(t % 5 == 0 ? 0.0f : 0.9f * std::sin(1.7f * float(t)));
  model.meshes.push_back(mesh);
  NodeData rigid;
  rigid.mesh = 0;
  rigid.translation = glm::vec3(3.0f, 0.5f, -1.0f);
  rigid.rotation = glm::angleAxis(0.6f, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  rigid.scale = glm::vec3(1.0f, 2.5f, 0.5f);
  rigid.morphWeights = mesh.morphWeights;
  for (float& w : rigid.morphWeights) w = -w;
  model.nodes.push_back(rigid);
  NodeData skinned;
  skinned.mesh = 0;
  skinned.skin = 0;
  skinned.morphWeights = mesh.morphWeights;
  model.nodes.push_back(skinned);
  SkinData skin;
  for (int j = 0; j < 4; ++j) {
    skin.joints.push_back(j);
    skin.inverseBinds.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.6f * float(j), 0.0f)));
  }
  model.skins.push_back(skin);
  model.sceneRoots = {0, 4, 5};
  return model;
}

std::string samplesDir() { return std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples"; }

}  // namespace

class GpuMorph : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuMorph);

TEST_P(GpuMorph, ManyTargetsRigidAndSkinnedMatchCpu) {
  const Counts counts = compareModel(manyTargetModel(), -1, 0.0);
  // Rigid: colour + depth; skinned: LBS and DQS, colour + depth.
  EXPECT_EQ(counts.positions, 6);
  EXPECT_EQ(counts.normals, 2);
}

TEST_P(GpuMorph, MorphInterpolationMatchesCpu) {
  auto model = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/tests/conformance/morph_poses/MorphInterpolation.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  for (int clip = 0; clip < 3; ++clip)
    for (double t : {0.5, 1.25}) EXPECT_EQ(compareModel(*model, clip, t).positions, 2 * 2 + 4) << clip << " " << t;
}

TEST_P(GpuMorph, AnimatedMorphCubeMatchesCpu) {
  const std::string path = samplesDir() + "/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (../shared/gltf-samples absent)";
  auto model = loadGltf(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  for (double t : {0.0, 1.05, 2.113, 3.15}) EXPECT_EQ(compareModel(*model, 0, t).normals, 1) << t;
}

TEST_P(GpuMorph, MorphPrimitivesTestMatchesCpu) {
  const std::string path = samplesDir() + "/MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (../shared/gltf-samples absent)";
  auto model = loadGltf(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(compareModel(*model, -1, 0.0).positions, 4);  // two primitives, colour + depth
}

// Normal maps: the tangent is morphed by the TANGENT targets, then skinned like a
// direction (d -> skin(p + d) - skin(p), LBS being linear in p and DQS not
// depending on it), or taken by the node's matrix when rigid.
TEST_P(GpuMorph, TangentsAreMorphedThenSkinned) {
  const ModelData model = manyTargetModel();
  auto animated = buildAnimatedModel(model);
  ASSERT_TRUE(animated.ok()) << animated.error().message;
  auto gpu = GpuModel::upload(model);
  ASSERT_TRUE(gpu.ok()) << gpu.error().message;
  ShaderVariants variants(test::shaderDir());
  const ModelPose pose = poseModel(*animated, -1, 0.0);
  const PrimitiveData& prim = model.meshes[0].primitives[0];
  const GpuPrimitive& gpuPrim = gpu->meshes()[0][0];
  ASSERT_TRUE(gpuPrim.hasTangents);
  const Palettes palettes = palettesOf(animated->skins[0], pose);
  for (size_t n : {size_t(4), size_t(5)}) {
    const std::span<const float> weights = animated->morphs.of(pose.weights, int(n));
    std::vector<glm::vec3> positions(prim.positions.size());
    std::vector<glm::vec4> tangents(prim.tangents.size());
    ASSERT_TRUE((MorphJob{weights, prim.positions, prim.morphPositions, positions, {}, {}, {}, prim.tangents,
                          prim.morphTangents, tangents}
                     .run()));
    const glm::mat4 world = pose.models[size_t(animated->skeleton.jointOfRaw(int(n)))];
    for (SkinMode mode : n == 4 ? std::vector<SkinMode>{SkinMode::None}
                                : std::vector<SkinMode>{SkinMode::Linear, SkinMode::DualQuat}) {
      ShaderVariant variant = primitiveVariant(model, model.nodes[n], prim, mode, false);
      variant.normalMap = true;  // no material asks for one; the variant is what is tested
      SCOPED_TRACE(variant.describe());
      const CaptureInputs inputs{palettes.palette, palettes.dualQuats, weights, n == 4 ? world : glm::mat4(1.0f)};
      const auto gpuTangents = captureVarying<glm::vec4>(variants, gpuPrim, inputs, variant, "v_tangent");
      ASSERT_EQ(gpuTangents.size(), tangents.size());
      std::vector<glm::vec3> expected(tangents.size());
      if (n == 4) {
        for (size_t v = 0; v < tangents.size(); ++v) expected[v] = glm::mat3(world) * glm::vec3(tangents[v]);
      } else {
        std::vector<glm::vec3> tips(positions.size()), base(positions.size()), skinnedTips(positions.size());
        for (size_t v = 0; v < positions.size(); ++v) tips[v] = positions[v] + glm::vec3(tangents[v]);
        SkinningJob job;
        job.method = mode == SkinMode::DualQuat ? SkinningMethod::DualQuat : SkinningMethod::Linear;
        job.influences = prim.influences;
        job.joints = prim.joints;
        job.weights = prim.weights;
        job.palette = palettes.palette;
        job.dualQuats = palettes.dualQuats;
        job.positions = positions;
        job.outPositions = base;
        ASSERT_TRUE(job.run());
        job.positions = tips;
        job.outPositions = skinnedTips;
        ASSERT_TRUE(job.run());
        for (size_t v = 0; v < tangents.size(); ++v) expected[v] = skinnedTips[v] - base[v];
      }
      double worst = 0.0;
      for (size_t v = 0; v < tangents.size(); ++v) {
        worst = std::max(worst, double(glm::length(glm::vec3(gpuTangents[v]) - expected[v])));
        EXPECT_EQ(std::abs(gpuTangents[v].w), 1.0f) << v;  // handedness passes through
      }
      std::printf("morphed tangent %s, GPU vs CPU: largest error %.3g\n", variant.describe().c_str(), worst);
      EXPECT_LE(worst, 1e-5);
    }
  }
}

// The renderer's own path: CharacterInstance uploads the evaluated weights and
// draws the MORPH variants, named "+morph"; unmorphed primitives do not pay.
TEST_P(GpuMorph, CharacterDrawsTheMorphVariant) {
  auto model = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/tests/conformance/morph_poses/MorphInterpolation.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  auto asset = CharacterAsset::create(*model);
  ASSERT_TRUE(asset.ok()) << asset.error().message;
  CharacterInstance instance(*asset);
  instance.play(2);
  instance.player().seek(1.25);
  ASSERT_TRUE(instance.evaluate().ok());
  auto expected = poseModel((*asset)->animated, 2, 1.25).weights;
  ASSERT_EQ(instance.morphWeights().size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(instance.morphWeights()[i], expected[i]) << i;
  instance.place(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 5.0));
  auto target = RenderTarget::create(32, 32, 1);
  ASSERT_TRUE(target.ok());
  target->bind();
  // The scene programs, as a scene's colour pass draws with them: the frame block
  // bound, back faces culled (the strip's default material is one-sided).
  ShaderVariants variants(test::shaderDir());
  const gl::Buffer frame = test::bindFrameBlock();
  glEnable(GL_CULL_FACE);
  const Status drawn = instance.draw(variants, SkinMode::Linear, {});
  glDisable(GL_CULL_FACE);
  ASSERT_TRUE(drawn.ok()) << drawn.error().message;
  std::vector<std::string> names;
  for (const ShaderVariant& v : variants.built()) names.push_back(v.describe());
  EXPECT_EQ(names, (std::vector<std::string>{"static+morph+onesided", "lbs4+morph+onesided"}));
  // A model without targets draws as before.
  EXPECT_EQ((ShaderVariant{4, SkinMode::DualQuat}.describe()), "dqs4");
}

// A triangle whose top vertex one target lifts by 1, in a 2 s clip whose weight
// spikes to 1 at 0.05 s and is back to 0 at 0.1 s: between the bounds' even samples.
ModelData spikeModel() {
  ModelData model;
  model.path = "spike.gltf";
  PrimitiveData prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  prim.morphTargets = 1;
  prim.morphPositions = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  MeshData mesh;
  mesh.primitives.push_back(prim);
  mesh.morphWeights = {0.0f};
  model.meshes.push_back(mesh);
  NodeData node;
  node.mesh = 0;
  node.morphWeights = {0.0f};
  model.nodes.push_back(node);
  model.sceneRoots = {0};
  AnimationData spike;
  spike.morphChannels.push_back({0, Interpolation::Linear, {0.0f, 0.05f, 0.1f, 2.0f}, 1, {0, 1, 0, 0}});
  spike.duration = 2.0f;
  model.animations.push_back(spike);
  return model;
}

// The culling bounds hold every morphed vertex of every pose: sampled densely here,
// at 1 ms, for STEP and LINEAR weights, whose extremes lie on keys. (Clips that
// also turn joints are left out: a vertex swinging on an arc bulges past the
// poses the bounds sample, morph targets or not.)
TEST_P(GpuMorph, BoundsHoldEveryMorphedPose) {
  std::vector<std::pair<std::string, std::vector<int>>> models{
      {"", {0}}, {std::string(ENGINE_SOURCE_DIR) + "/tests/conformance/morph_poses/MorphInterpolation.gltf", {0}}};
  const std::string cube = samplesDir() + "/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb";
  if (std::filesystem::exists(cube)) models.push_back({cube, {0}});
  for (const auto& [path, clips] : models) {
    auto model = path.empty() ? Result<ModelData>(spikeModel()) : loadGltf(path);
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto asset = CharacterAsset::create(*model);
    ASSERT_TRUE(asset.ok()) << asset.error().message;
    auto bounds = (*asset)->boundsOfAllPoses();
    ASSERT_TRUE(bounds.ok()) << bounds.error().message;
    const float slack = 1e-6f * glm::length(bounds->max - bounds->min);
    for (int clip : clips) {
      const double duration = (*asset)->animated.clips[size_t(clip)].duration();
      for (double t = 0.0; t <= duration; t += 1e-3) {
        auto pose = dumpPose(*model, clip, t, LoopMode::Clamp);
        ASSERT_TRUE(pose.ok()) << pose.error().message;
        for (const auto& mesh : (*pose)["meshes"])
          for (size_t i = 0; i + 2 < mesh["positions"].size(); i += 3)
            for (int c = 0; c < 3; ++c) {
              const float x = mesh["positions"][i + size_t(c)].get<float>();
              ASSERT_GE(x, bounds->min[c] - slack) << path << " clip " << clip << " t " << t;
              ASSERT_LE(x, bounds->max[c] + slack) << path << " clip " << clip << " t " << t;
            }
      }
    }
  }
}
