#include "scene/model_asset.h"

#include <algorithm>

#include "anim/jobs.h"
#include "anim/player.h"
#include "asset/gltf_loader.h"

namespace engine {

Result<std::shared_ptr<const ModelAsset>> ModelAsset::create(ModelData model) {
  auto animated = buildAnimatedModel(model);
  if (!animated) return animated.error();
  return std::shared_ptr<const ModelAsset>(
      std::make_shared<ModelAsset>(ModelAsset{std::move(model), std::move(animated).value()}));
}

Result<std::shared_ptr<const ModelAsset>> ModelAsset::load(const std::string& path) {
  auto model = loadGltf(path);
  if (!model) return model.error();
  return create(std::move(model).value());
}

Status jointsFromLocals(const ModelAsset& asset, std::span<const Srt> locals, std::span<glm::mat4> joints) {
  return runJob(LocalToModelJob{asset.animated.skeleton.parents(), locals, glm::mat4(1.0f), joints}, asset.model.path);
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

// Grows `b` by every vertex of `asset` in `pose`.
Status addPoseToBounds(const ModelAsset& asset, const Pose& pose, ModelAsset::Bounds& b) {
  const ModelData& model = asset.model;
  std::vector<glm::vec3> posed;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
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
        for (const glm::vec3& p : posed) {
          b.min = glm::min(b.min, p);
          b.max = glm::max(b.max, p);
        }
      }
    }
  }
  return Ok{};
}

}  // namespace

// Clip times are sampled as they are, not wrapped: the last sample is the clip's
// end, which wrapping would turn back into its start.
Result<ModelAsset::Bounds> ModelAsset::boundsOfAllPoses(int samples) const {
  Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  const Skeleton& skeleton = animated.skeleton;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  Pose pose{std::vector<glm::mat4>(locals.size()), animated.morphs.restWeights};
  if (auto s = jointsFromLocals(*this, locals, pose.joints); !s) return s.error();
  if (auto s = addPoseToBounds(*this, pose, b); !s) return s.error();
  for (const Clip& clip : animated.clips) {
    for (const double time : boundsSampleTimes(clip, samples)) {
      const std::string where = model.path + ": clip " + clip.name();
      if (auto s = runJob(SamplingJob{&clip, time, skeleton.restPose(), locals}, where); !s) return s.error();
      if (auto s = runJob(MorphSamplingJob{&clip, time, animated.morphs.restWeights, pose.morphWeights}, where); !s)
        return s.error();
      if (auto s = jointsFromLocals(*this, locals, pose.joints); !s) return s.error();
      if (auto s = addPoseToBounds(*this, pose, b); !s) return s.error();
    }
  }
  if (b.min.x > b.max.x) b = Bounds{};
  return b;
}

}  // namespace engine
