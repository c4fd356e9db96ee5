#include "anim/model_builder.h"

namespace engine {

RawSkeleton makeRawSkeleton(const ModelData& model) {
  RawSkeleton raw;
  for (const NodeData& node : model.nodes) {
    raw.parents.push_back(node.parent);
    raw.restPose.push_back(Srt{node.scale, node.rotation, node.translation});
    raw.names.push_back(node.name);
  }
  return raw;
}

MorphLayout makeMorphLayout(const ModelData& model) {
  MorphLayout layout;
  layout.first.assign(model.nodes.size(), -1);
  layout.targets.assign(model.nodes.size(), 0);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const std::vector<float>& weights = model.nodes[n].morphWeights;
    if (weights.empty()) continue;
    layout.first[n] = static_cast<int>(layout.restWeights.size());
    layout.targets[n] = static_cast<int>(weights.size());
    layout.restWeights.insert(layout.restWeights.end(), weights.begin(), weights.end());
  }
  return layout;
}

RawClip makeRawClip(const AnimationData& animation) {
  RawClip raw;
  raw.name = animation.name;
  for (const ChannelData& channel : animation.channels)
    raw.tracks.push_back(Track{channel.node, channel.path, channel.interpolation, channel.times, channel.values});
  for (const MorphChannelData& channel : animation.morphChannels)
    raw.morphTracks.push_back(
        MorphTrack{channel.node, -1, channel.targets, channel.interpolation, channel.times, channel.values});
  return raw;
}

namespace {

// AnimatedModel::staticModels: the rest pose's model matrices up to the first joint
// any clip drives. Depth-first order puts a joint's ancestors before it, so those
// joints are a skeleton of their own.
Status findStaticModels(AnimatedModel& out) {
  const std::span<const int> parents = out.skeleton.parents();
  std::size_t first = parents.size();
  for (const Clip& clip : out.clips)
    for (const Track& track : clip.tracks()) first = std::min(first, static_cast<std::size_t>(track.joint));
  out.staticModels.resize(first);
  return runJob(LocalToModelJob{parents.first(first), out.skeleton.restPose().first(first), glm::mat4(1.0f),
                                out.staticModels},
                "rest pose");
}

}  // namespace

Result<AnimatedModel> buildAnimatedModel(const ModelData& model) {
  auto skeleton = Skeleton::build(makeRawSkeleton(model));
  if (!skeleton) return makeError(model.path + ": " + skeleton.error().message);
  AnimatedModel out{std::move(skeleton.value()), {}, {}, makeMorphLayout(model)};
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    auto clip = Clip::build(makeRawClip(model.animations[a]), out.skeleton, out.morphs);
    if (!clip) return makeError(model.path + ": animation " + std::to_string(a) + ": " + clip.error().message);
    out.clips.push_back(std::move(clip.value()));
  }
  if (auto s = findStaticModels(out); !s) return makeError(model.path + ": " + s.error().message);
  for (const SkinData& skin : model.skins) {
    Skin runtime;
    for (int node : skin.joints) runtime.joints.push_back(out.skeleton.jointOfRaw(node));
    runtime.inverseBinds = skin.inverseBinds;
    out.skins.push_back(std::move(runtime));
  }
  return out;
}

Result<int> findClip(const AnimatedModel& animated, const std::string& wanted, const std::string& modelPath) {
  const int count = int(animated.clips.size());
  if (wanted.empty()) return count > 0 ? 0 : -1;
  const bool numeric = wanted.find_first_not_of("-0123456789") == std::string::npos;
  if (numeric && wanted.size() < 10) {
    const int index = std::stoi(wanted);
    if (index >= -1 && index < count) return index;
  }
  std::string names;
  for (int i = 0; i < count; ++i) {
    const std::string& name = animated.clips[size_t(i)].name();
    if (name == wanted) return i;
    names += (i ? ", " : "") + name;
  }
  const std::string file = modelPath.substr(modelPath.find_last_of('/') + 1);
  return makeError("no clip \"" + wanted + "\" in " + file + "; clips are: " + (names.empty() ? "(none)" : names) +
                   " (or an index, -1 = rest pose)");
}

namespace {

// Skins `positions` (and `normals`, when `outNormals` is not empty) with the
// primitive's joints and weights; the outputs may be the inputs.
bool skinVertices(const PrimitiveData& prim, const Skin& skin, std::span<const glm::mat4> models,
                  SkinningMethod method, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                  std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals) {
  std::vector<glm::mat4> palette(skin.joints.size());
  if (!SkinningPaletteJob{models, skin.joints, skin.inverseBinds, palette}.run()) return false;
  std::vector<DualQuat> dualQuats;
  if (method == SkinningMethod::DualQuat) {
    dualQuats.resize(palette.size());
    if (!DualQuatPaletteJob{palette, dualQuats}.run()) return false;
  }
  SkinningJob job;
  job.method = method;
  job.influences = prim.influences;
  job.positions = positions;
  if (!outNormals.empty()) job.normals = normals;
  job.joints = prim.joints;
  job.weights = prim.weights;
  job.palette = palette;
  job.dualQuats = dualQuats;
  job.outPositions = outPositions;
  job.outNormals = outNormals;
  return job.run();
}

// A zero normal (a degenerate matrix, or targets that cancel it) stays zero
// instead of becoming NaN. (jobs.cpp's unitOrZero divides by the square root, and
// its last bits differ: the skinning job's and these normals each keep their own.)
glm::vec3 normalizedOrZero(const glm::vec3& v) { return glm::dot(v, v) > 0.0f ? glm::normalize(v) : glm::vec3(0.0f); }

// glTF applies a rigid node's whole matrix: the normals take its inverse
// transpose, renormalised.
void moveRigidly(const glm::mat4& world, std::span<glm::vec3> positions, std::span<glm::vec3> normals) {
  for (glm::vec3& p : positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
  if (normals.empty()) return;
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
  for (glm::vec3& n : normals) n = normalizedOrZero(normalMatrix * n);
}

}  // namespace

bool skinPrimitive(const PrimitiveData& prim, const Skin& skin, std::span<const glm::mat4> models,
                   SkinningMethod method, std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals) {
  return skinVertices(prim, skin, models, method, prim.positions, prim.normals, outPositions, outNormals);
}

bool posePrimitive(const PrimitiveData& prim, const PrimitivePose& pose, std::span<glm::vec3> outPositions,
                   std::span<glm::vec3> outNormals) {
  const bool withNormals = !outNormals.empty();
  if (withNormals && outNormals.size() != prim.normals.size()) return false;
  const bool morphed = !pose.morphWeights.empty();
  if (morphed && pose.morphWeights.size() != static_cast<std::size_t>(prim.morphTargets)) return false;
  MorphJob morph;
  morph.weights = pose.morphWeights;
  morph.positions = prim.positions;
  morph.positionDeltas = morphed ? std::span<const glm::vec3>(prim.morphPositions) : std::span<const glm::vec3>();
  morph.outPositions = outPositions;
  if (withNormals) {
    morph.normals = prim.normals;
    morph.normalDeltas = morphed ? std::span<const glm::vec3>(prim.morphNormals) : std::span<const glm::vec3>();
    morph.outNormals = outNormals;
  }
  if (!morph.run()) return false;
  if (pose.skin == nullptr) {
    moveRigidly(pose.world, outPositions, outNormals);
    return true;
  }
  // Skinned in place, from the morphed vertices.
  if (!skinVertices(prim, *pose.skin, pose.models, pose.method, outPositions, outNormals, outPositions, outNormals))
    return false;
  // Linear blend skinning renormalises; dual quaternions only rotate, and a
  // morphed normal need not be unit length.
  if (morphed)
    for (glm::vec3& n : outNormals) n = normalizedOrZero(n);
  return true;
}

}  // namespace engine
