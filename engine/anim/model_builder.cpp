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

}  // namespace engine
