// Animation: each clip's node and morph weights channels, their samplers'
// interpolation, key times and values.
#include <algorithm>
#include <cmath>

#include "asset/gltf_loader_impl.h"

namespace engine::gltf_loader {

Status Converter::convertAnimations() {
  for (std::size_t a = 0; a < gltf_.animations.size(); ++a) {
    AnimationData anim;
    anim.name = gltf_.animations[a].name;
    for (std::size_t c = 0; c < gltf_.animations[a].channels.size(); ++c) {
      if (Status s = convertChannel(gltf_.animations[a], c, anim, "animation " + str(a) + " channel " + str(c)); !s)
        return s;
    }
    out_.animations.push_back(std::move(anim));
  }
  return Ok{};
}

// Adds channel `c` to `anim` as a node or a morph weights channel (or skips it
// with a warning when it has no target node).
Status Converter::convertChannel(const tinygltf::Animation& src, std::size_t c, AnimationData& anim, const std::string& name) {
  const tinygltf::AnimationChannel& ch = src.channels[c];
  if (ch.target_node < 0) {
    warn(name + ": has no target node; ignored");
    return Ok{};
  }
  if (!validIndex(ch.target_node, out_.nodes.size()))
    return error(name + ": target node " + str(ch.target_node) + " does not exist");
  if (!validIndex(ch.sampler, src.samplers.size()))
    return error(name + ": sampler " + str(ch.sampler) + " does not exist");
  const tinygltf::AnimationSampler& sampler = src.samplers[static_cast<std::size_t>(ch.sampler)];
  const std::string samplerName = name + " sampler " + str(ch.sampler);
  if (ch.target_path == "weights") {
    MorphChannelData channel;
    if (Status s = convertMorphChannel(ch, sampler, channel, name, samplerName); !s) return s;
    anim.duration = std::max(anim.duration, channel.times.back());
    anim.morphChannels.push_back(std::move(channel));
    return Ok{};
  }
  ChannelData channel;
  channel.node = ch.target_node;
  if (ch.target_path == "translation") channel.path = AnimPath::Translation;
  else if (ch.target_path == "rotation") channel.path = AnimPath::Rotation;
  else if (ch.target_path == "scale") channel.path = AnimPath::Scale;
  else return error(name + ": unknown path \"" + ch.target_path + "\"");
  if (Status s = readKeys(sampler, samplerName, channel.interpolation, channel.times); !s) return s;
  if (Status s = readValues(sampler.output, channel, samplerName + " output"); !s) return s;
  anim.duration = std::max(anim.duration, channel.times.back());
  anim.channels.push_back(std::move(channel));
  return Ok{};
}

// A sampler's interpolation and key times, the same for node and weights channels.
Status Converter::readKeys(const tinygltf::AnimationSampler& sampler, const std::string& name, Interpolation& interpolation,
                           std::vector<float>& times) {
  if (sampler.interpolation == "STEP") interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE") interpolation = Interpolation::CubicSpline;
  else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") interpolation = Interpolation::Linear;
  else return error(name + ": unknown interpolation \"" + sampler.interpolation + "\"");
  auto keys = readTimes(sampler.input, name + " input");
  if (!keys) return keys.error();
  times = std::move(keys).value();
  return Ok{};
}

// A `weights` channel drives every target of the node's mesh: the node must
// have a mesh with targets, and the output holds one weight per target per key
// (three blocks of them per key for CUBICSPLINE).
Status Converter::convertMorphChannel(const tinygltf::AnimationChannel& ch, const tinygltf::AnimationSampler& sampler,
                                      MorphChannelData& channel, const std::string& name, const std::string& samplerName) {
  const NodeData& node = out_.nodes[static_cast<std::size_t>(ch.target_node)];
  const int targets = node.mesh < 0 ? 0 : targetCount(out_.meshes[static_cast<std::size_t>(node.mesh)]);
  if (targets == 0)
    return error(name + ": animates the weights of node " + str(ch.target_node) +
                 (node.mesh < 0 ? ", which has no mesh" : ", whose mesh " + str(node.mesh) + " has no morph targets"));
  channel.node = ch.target_node;
  channel.targets = targets;
  if (Status s = readKeys(sampler, samplerName, channel.interpolation, channel.times); !s) return s;
  const std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
  const std::size_t expected = channel.times.size() * perKey * static_cast<std::size_t>(targets);
  auto values = readFloats(sampler.output, 1, 0, samplerName + " output");
  if (!values) return values.error();
  if (values->size() != expected)
    return error(samplerName + " output: " + str(values->size()) + " weights for " + str(channel.times.size()) +
                 " keys of " + str(targets) + " morph targets (" + str(expected) + " expected)");
  channel.values = std::move(values).value();
  return Ok{};
}

Result<std::vector<float>> Converter::readTimes(int accessor, const std::string& name) {
  auto times = readAccessor(gltf_, accessor, file_ + ": " + name);
  if (!times) return times.error();
  if (times->components != 1) return error(name + ": key times must be SCALAR");
  std::vector<float> out(times->count);
  for (std::size_t k = 0; k < times->count; ++k) {
    float t = static_cast<float>(times->values[k]);
    if (!std::isfinite(t)) return error(name + ": key " + str(k) + " time is NaN or infinite");
    if (t < 0.0f) return error(name + ": key " + str(k) + " time " + std::to_string(t) + " is negative");
    if (k > 0 && t < out[k - 1])
      return error(name + ": key " + str(k) + " time " + std::to_string(t) +
                   " is before the previous key (times must be sorted)");
    out[k] = t;
  }
  return out;
}

Status Converter::readValues(int accessor, ChannelData& channel, const std::string& name) {
  int components = channel.path == AnimPath::Rotation ? 4 : 3;
  std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
  auto values = readFloats(accessor, components, channel.times.size() * perKey, name);
  if (!values) return values.error();
  std::size_t count = values->size() / static_cast<std::size_t>(components);
  channel.values.resize(count, glm::vec4(0.0f));
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < components; ++c)
      channel.values[i][c] = (*values)[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)];
  return Ok{};
}

}  // namespace engine::gltf_loader
