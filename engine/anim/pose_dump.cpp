#include "anim/pose_dump.h"

#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"

namespace engine {
namespace {

nlohmann::json matrixJson(const glm::mat4& m) {
  nlohmann::json out = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out.push_back(m[c][r]);
  return out;
}

nlohmann::json positionsJson(const std::vector<glm::vec3>& positions) {
  nlohmann::json out = nlohmann::json::array();
  for (const glm::vec3& p : positions) {
    out.push_back(p.x);
    out.push_back(p.y);
    out.push_back(p.z);
  }
  return out;
}

nlohmann::json weightsJson(std::span<const float> weights) {
  nlohmann::json out = nlohmann::json::array();
  for (float w : weights) out.push_back(w);
  return out;
}

}  // namespace

Result<nlohmann::json> dumpPose(const ModelData& model, int animation, double time, LoopMode loop) {
  auto built = buildAnimatedModel(model);
  if (!built) return built.error();
  const Skeleton& skeleton = built->skeleton;
  if (animation < -1 || animation >= static_cast<int>(built->clips.size()))
    return makeError(model.path + ": animation " + std::to_string(animation) + " does not exist (" +
                     std::to_string(built->clips.size()) + " animations)");

  std::size_t count = static_cast<std::size_t>(skeleton.jointCount());
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  const MorphLayout& morphs = built->morphs;
  std::vector<float> weights = morphs.restWeights;
  nlohmann::json out;
  out["time"] = time;
  out["anim"] = animation;
  if (animation >= 0) {
    const Clip& clip = built->clips[static_cast<std::size_t>(animation)];
    double local = wrapTime(time, clip.duration(), loop);
    SamplingJob sample{&clip, local, skeleton.restPose(), locals};
    if (!sample.run()) return makeError(model.path + ": sampling failed");
    if (!MorphSamplingJob{&clip, local, morphs.restWeights, weights}.run())
      return makeError(model.path + ": morph weight sampling failed");
    out["animation"] = {{"duration", clip.duration()},
                        {"localTime", local},
                        {"loop", loop == LoopMode::Clamp ? "clamp" : loop == LoopMode::PingPong ? "pingpong" : "repeat"}};
  }
  std::vector<glm::mat4> models(count);
  LocalToModelJob toModel{skeleton.parents(), locals, glm::mat4(1.0f), models};
  if (!toModel.run()) return makeError(model.path + ": local-to-model failed");

  auto world = [&](std::size_t node) -> const glm::mat4& {
    return models[static_cast<std::size_t>(skeleton.jointOfRaw(static_cast<int>(node)))];
  };
  out["nodes"] = nlohmann::json::array();
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    out["nodes"].push_back({{"node", n}, {"world", matrixJson(world(n))}});

  out["meshes"] = nlohmann::json::array();
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const MeshData& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
    const std::span<const float> nodeWeights = morphs.of(weights, static_cast<int>(n));
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const PrimitiveData& prim = mesh.primitives[p];
      bool skinned = node.skin >= 0 && prim.influences > 0;
      // EXT_mesh_gpu_instancing: one entry per instance, placed by world * instance
      // and numbered by "instance"; a node without instances has no such key.
      const std::span<const glm::mat4> instances = meshInstances(node);
      for (std::size_t i = 0; i < instances.size(); ++i) {
        PrimitivePose pose{nodeWeights, skinned ? &built->skins[static_cast<std::size_t>(node.skin)] : nullptr, models,
                           world(n) * instances[i]};
        std::vector<glm::vec3> positions(prim.positions.size());
        if (!posePrimitive(prim, pose, positions))
          return makeError(model.path + ": node " + std::to_string(n) + " primitive " + std::to_string(p) +
                           ": morphing or skinning failed");
        // As three.js's pose.mjs writes them: the mesh's target count and the
        // weights this instance was drawn with.
        nlohmann::json entry{{"node", n},
                             {"mesh", node.mesh},
                             {"primitive", p},
                             {"skinned", skinned},
                             {"morphTargets", prim.morphTargets},
                             {"morphWeights", weightsJson(nodeWeights)},
                             {"count", positions.size()},
                             {"positions", positionsJson(positions)}};
        if (!node.instances.empty()) entry["instance"] = i;
        out["meshes"].push_back(std::move(entry));
      }
    }
  }
  return out;
}

}  // namespace engine
