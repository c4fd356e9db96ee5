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

RawClip makeRawClip(const AnimationData& animation) {
  RawClip raw;
  raw.name = animation.name;
  for (const ChannelData& channel : animation.channels)
    raw.tracks.push_back(Track{channel.node, channel.path, channel.interpolation, channel.times, channel.values});
  return raw;
}

Result<AnimatedModel> buildAnimatedModel(const ModelData& model) {
  auto skeleton = Skeleton::build(makeRawSkeleton(model));
  if (!skeleton) return makeError(model.path + ": " + skeleton.error().message);
  AnimatedModel out{std::move(skeleton.value()), {}, {}};
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    auto clip = Clip::build(makeRawClip(model.animations[a]), out.skeleton);
    if (!clip) return makeError(model.path + ": animation " + std::to_string(a) + ": " + clip.error().message);
    out.clips.push_back(std::move(clip.value()));
  }
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

bool skinPrimitive(const PrimitiveData& prim, const Skin& skin, std::span<const glm::mat4> models,
                   SkinningMethod method, std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals) {
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
  job.positions = prim.positions;
  if (!outNormals.empty()) job.normals = prim.normals;
  job.joints = prim.joints;
  job.weights = prim.weights;
  job.palette = palette;
  job.dualQuats = dualQuats;
  job.outPositions = outPositions;
  job.outNormals = outNormals;
  return job.run();
}

}  // namespace engine
