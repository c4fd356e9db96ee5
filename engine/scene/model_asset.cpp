#include "scene/model_asset.h"

#include <algorithm>

#include "anim/jobs.h"
#include "anim/player.h"
#include "asset/gltf_loader.h"

namespace engine {

Result<std::shared_ptr<const ModelAsset>> ModelAsset::create(ModelData model) {
  auto animated = buildAnimatedModel(model);
  if (!animated) return animated.error();
  auto asset = std::make_shared<ModelAsset>(ModelAsset{std::move(model), std::move(animated).value(), {}});
  asset->materials = gltfMaterials(asset->model);
  return std::shared_ptr<const ModelAsset>(std::move(asset));
}

Result<std::shared_ptr<const ModelAsset>> ModelAsset::load(const std::string& path) {
  auto model = loadGltf(path);
  if (!model) return model.error();
  return create(std::move(model).value());
}

Status jointsFromLocals(const ModelAsset& asset, std::span<const Srt> locals, std::span<glm::mat4> joints) {
  return runJob(LocalToModelJob{asset.animated.skeleton.parents(), locals, glm::mat4(1.0f), joints,
                                asset.animated.staticModels},
                asset.model.path);
}

Status playerPose(const ModelAsset& asset, Player& player, bool bindPose, std::vector<Srt>& locals, Pose& pose) {
  const Skeleton& skeleton = asset.animated.skeleton;
  const auto rest = skeleton.restPose();
  locals.resize(rest.size());
  pose.morphWeights.resize(asset.animated.morphs.restWeights.size());
  if (bindPose || !player.clip() || !player.evaluate(locals, pose.morphWeights)) {
    std::copy(rest.begin(), rest.end(), locals.begin());
    pose.morphWeights = asset.animated.morphs.restWeights;
  }
  pose.joints.resize(locals.size());
  return jointsFromLocals(asset, locals, pose.joints);
}

Status samplePose(const ModelAsset& asset, int clip, double clipTime, std::vector<Srt>& locals, Pose& pose,
                  QuatInterpolation rotations) {
  const Skeleton& skeleton = asset.animated.skeleton;
  const MorphLayout& morphs = asset.animated.morphs;
  locals.assign(skeleton.restPose().begin(), skeleton.restPose().end());
  pose.morphWeights = morphs.restWeights;
  if (clip >= 0 && clip < int(asset.animated.clips.size())) {
    const Clip& c = asset.animated.clips[size_t(clip)];
    const double local = wrapTime(clipTime, c.duration(), LoopMode::Repeat);
    const std::string where = asset.model.path + ": clip " + c.name();
    if (auto s = runJob(SamplingJob{&c, local, skeleton.restPose(), locals, rotations}, where); !s) return s;
    if (auto s = runJob(MorphSamplingJob{&c, local, morphs.restWeights, pose.morphWeights}, where); !s) return s;
  }
  pose.joints.resize(locals.size());
  return jointsFromLocals(asset, locals, pose.joints);
}

namespace {

// The clip times that the bounds sample: `samples` + 1 evenly spaced, and every
// key of a morph track, where LINEAR weights (and so the vertices) peak.
std::vector<double> boundsSampleTimes(const Clip& clip, int samples) {
  std::vector<double> times;
  for (int i = 0; i <= samples; ++i) times.push_back(clip.duration() * double(i) / double(samples));
  for (const MorphTrack& track : clip.morphTracks()) times.insert(times.end(), track.times.begin(), track.times.end());
  return times;
}

// Every (node, instance, primitive) of `asset` posed on the CPU in `pose`, handed to
// `visit(mesh, primitive, positions)`.
Status forEachPosedPrimitive(const ModelAsset& asset, const Pose& pose,
                             const std::function<void(int, int, std::vector<glm::vec3>&)>& visit) {
  const ModelData& model = asset.model;
  std::vector<glm::vec3> posed;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& primitives = model.meshes[size_t(node.mesh)].primitives;
    for (size_t k = 0; k < primitives.size(); ++k) {
      const PrimitiveData& prim = primitives[k];
      const bool skinned = node.skin >= 0 && prim.influences > 0;
      const glm::mat4& world = pose.joints[size_t(asset.animated.skeleton.jointOfRaw(int(n)))];
      // Every EXT_mesh_gpu_instancing instance (world * instance), or the node once.
      for (const glm::mat4& instance : meshInstances(node)) {
        const PrimitivePose primPose{asset.animated.morphs.of(pose.morphWeights, int(n)),
                                     skinned ? &asset.animated.skins[size_t(node.skin)] : nullptr, pose.joints,
                                     world * instance};
        posed.resize(prim.positions.size());
        if (!posePrimitive(prim, primPose, posed))
          return makeError(model.path + ": node " + std::to_string(n) + ": morphing or skinning rejected its inputs");
        visit(node.mesh, int(k), posed);
      }
    }
  }
  return Ok{};
}

// Grows `b` by every vertex of `asset` in `pose`.
Status addPoseToBounds(const ModelAsset& asset, const Pose& pose, ModelAsset::Bounds& b) {
  return forEachPosedPrimitive(asset, pose, [&](int, int, std::vector<glm::vec3>& posed) {
    for (const glm::vec3& p : posed) {
      b.min = glm::min(b.min, p);
      b.max = glm::max(b.max, p);
    }
  });
}

}  // namespace

// Clip times are sampled as they are, not wrapped: the last sample is the clip's
// end, which wrapping would turn back into its start.
Status ModelAsset::forEachSampledPose(int samples, const std::function<Status(const Pose&)>& visit) const {
  const Skeleton& skeleton = animated.skeleton;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  Pose pose{std::vector<glm::mat4>(locals.size()), animated.morphs.restWeights};
  if (auto s = jointsFromLocals(*this, locals, pose.joints); !s) return s;
  if (auto s = visit(pose); !s) return s;
  for (const Clip& clip : animated.clips) {
    for (const double time : boundsSampleTimes(clip, samples)) {
      const std::string where = model.path + ": clip " + clip.name();
      if (auto s = runJob(SamplingJob{&clip, time, skeleton.restPose(), locals}, where); !s) return s;
      if (auto s = runJob(MorphSamplingJob{&clip, time, animated.morphs.restWeights, pose.morphWeights}, where); !s)
        return s;
      if (auto s = jointsFromLocals(*this, locals, pose.joints); !s) return s;
      if (auto s = visit(pose); !s) return s;
    }
  }
  return Ok{};
}

Result<ModelAsset::Bounds> ModelAsset::boundsOfAllPoses(int samples) const {
  Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  if (auto s = forEachSampledPose(samples, [&](const Pose& pose) { return addPoseToBounds(*this, pose, b); }); !s)
    return s.error();
  if (b.min.x > b.max.x) b = Bounds{};
  return b;
}

Result<ModelAsset::LevelsOfDetail> ModelAsset::levelsOfDetail(int samples) const {
  auto bounds = boundsOfAllPoses();
  if (!bounds) return bounds.error();
  const float diagonal = glm::length(bounds->max - bounds->min);
  // shapes[mesh][primitive]: the primitive's positions in every pose of every node
  // (and instance) that draws it.
  std::vector<std::vector<std::vector<std::vector<glm::vec3>>>> shapes(model.meshes.size());
  for (size_t m = 0; m < model.meshes.size(); ++m) shapes[m].resize(model.meshes[m].primitives.size());
  auto addShapes = [&](const Pose& pose) -> Status {
    return forEachPosedPrimitive(*this, pose, [&](int mesh, int primitive, std::vector<glm::vec3>& posed) {
      shapes[size_t(mesh)][size_t(primitive)].push_back(posed);
    });
  };
  if (auto s = forEachSampledPose(samples, addShapes); !s) return s.error();
  LevelsOfDetail levels(model.meshes.size());
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) {
      const auto& posed = shapes[m][k];
      if (posed.empty()) {  // drawn by no node: measured as it is
        levels[m].push_back(simplifiedLevels(model.meshes[m].primitives[k]));
      } else {
        levels[m].push_back(simplifiedLevels(model.meshes[m].primitives[k], posed, 1.0f / std::max(diagonal, 1e-30f)));
      }
    }
  return levels;
}

}  // namespace engine
