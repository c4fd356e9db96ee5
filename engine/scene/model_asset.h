#pragma once
// A glTF model as every renderer uses it, loaded once per file however many
// instances a scene places: the file's data, its runtime skeleton, clips, skins and
// morph layout, and the one way a pose of it is sampled. GL-free: the rasterizer
// uploads it (render/character.h), the tracers skin it on the CPU.
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "anim/clip.h"
#include "anim/model_builder.h"
#include "anim/player.h"
#include "asset/mesh_lod.h"
#include "asset/model_data.h"
#include "core/result.h"
#include "scene/materials.h"

namespace engine {

struct Pose;

struct ModelAsset {
  ModelData model;
  AnimatedModel animated;
  // The model's materials as both renderers shade them (scene/materials.h), their
  // textures pointing into model.images: made once by create, for the asset where
  // it lies (a copy of the asset would point into the original's images).
  std::vector<SceneMaterial> materials;

  // Builds the runtime animation data of `model`.
  static Result<std::shared_ptr<const ModelAsset>> create(ModelData model);
  // loadGltf, then create.
  static Result<std::shared_ptr<const ModelAsset>> load(const std::string& path);

  // Model-space bounds that hold every pose of every clip (sampled `samples`
  // times per clip, every morph key, and the rest pose), for culling skinned meshes.
  struct Bounds {
    glm::vec3 min{0.0f}, max{0.0f};
  };
  Result<Bounds> boundsOfAllPoses(int samples = 24) const;
  // Every mesh primitive's levels of detail (asset/mesh_lod.h), [mesh][primitive],
  // their errors measured in the rest pose and `samples` + 1 poses of every clip
  // (and every morph key), relative to the diagonal of boundsOfAllPoses: the size a
  // renderer sees an instance by. Made on demand: it costs a simplification and a
  // distance search per level and pose.
  using LevelsOfDetail = std::vector<std::vector<std::vector<MeshLod>>>;
  Result<LevelsOfDetail> levelsOfDetail(int samples = 8) const;
  // Calls `visit` with the rest pose, then `samples` + 1 poses of every clip and its
  // morph keys: what the bounds and the levels of detail are measured over.
  Status forEachSampledPose(int samples, const std::function<Status(const Pose&)>& visit) const;
};

// A pose of a model: every runtime joint's matrix in model space (the instance's
// root not applied: each view applies it relative to its own eye) and every
// morphing node's weights, in the asset's MorphLayout order.
struct Pose {
  std::vector<glm::mat4> joints;
  std::vector<float> morphWeights;
};

// The pose of `asset` at `clipTime` of `clip`, wrapped into the clip (looping);
// clip -1 is the rest pose. `locals` is scratch, resized as needed.
// `rotations`: slerp (exact) or nlerp (the shortcut the trade table measures).
Status samplePose(const ModelAsset& asset, int clip, double clipTime, std::vector<Srt>& locals, Pose& pose,
                  QuatInterpolation rotations = QuatInterpolation::Slerp);
// The pose `player` plays now (its clips, cross-fades and loop mode), or the rest
// pose when `bindPose`, nothing plays or the player has no clip: the viewer's and
// the characters' way to pose. `locals` is scratch, resized as needed.
Status playerPose(const ModelAsset& asset, Player& player, bool bindPose, std::vector<Srt>& locals, Pose& pose);
// The model-space joint matrices of `locals` (LocalToModelJob, identity root): the
// rest pose or a pose of the asset's clips, whose static ancestors are copied from
// AnimatedModel::staticModels rather than computed.
Status jointsFromLocals(const ModelAsset& asset, std::span<const Srt> locals, std::span<glm::mat4> joints);

}  // namespace engine
