#pragma once
// Turns a loaded glTF model into runtime animation data: every node becomes a
// joint of one Skeleton (so non-joint animated nodes move too), each glTF
// animation a Clip, each glTF skin a Skin of runtime joint indices.
#include <vector>

#include "anim/clip.h"
#include "anim/jobs.h"
#include "anim/skeleton.h"
#include "asset/model_data.h"
#include "core/result.h"

namespace engine {

struct AnimatedModel {
  Skeleton skeleton;          // joint j is glTF node skeleton.rawOfJoint(j)
  std::vector<Clip> clips;    // one per glTF animation, same order
  std::vector<Skin> skins;    // one per glTF skin, same order
  MorphLayout morphs;         // each mesh node's morph weights in one flat array
  // The model matrices (identity root) of the joints before the first one a clip
  // drives: their ancestors come before them, so nothing moves them (COLLADA2GLTF's
  // Z_UP, Blender's Armature). LocalToModelJob::fixed copies them every frame.
  std::vector<glm::mat4> staticModels{};
};

RawSkeleton makeRawSkeleton(const ModelData& model);
// Every node whose mesh has morph targets, in node order, with its default weights.
MorphLayout makeMorphLayout(const ModelData& model);
RawClip makeRawClip(const AnimationData& animation);
Result<AnimatedModel> buildAnimatedModel(const ModelData& model);

// Skins one glTF primitive on the CPU for joint matrices `models` (palette, then
// SkinningJob): the one path that the pose dump, the ray tracer, bounds and
// benchmarks share with what the GPU computes. `outNormals` may be empty. False
// when the spans do not fit.
[[nodiscard]] bool skinPrimitive(const PrimitiveData& prim, const Skin& skin, std::span<const glm::mat4> models,
                   SkinningMethod method, std::span<glm::vec3> outPositions,
                   std::span<glm::vec3> outNormals = {});

// One (node, primitive) instance posed on the CPU in glTF's order: morphed by
// `morphWeights` (the node's, one per target; empty leaves the primitive
// unmorphed), then skinned by `skin` when it is given (the node's own transform
// ignored, as glTF requires) or moved rigidly by `world`. `outNormals` may be
// empty; normals come out unit length. The path that the pose dump, the ray
// tracer and the bounds share. False when the spans do not fit.
struct PrimitivePose {
  std::span<const float> morphWeights;
  const Skin* skin = nullptr;
  std::span<const glm::mat4> models;  // joint matrices, for `skin`
  glm::mat4 world{1.0f};              // the node's, without `skin`
  SkinningMethod method = SkinningMethod::Linear;
};
[[nodiscard]] bool posePrimitive(const PrimitiveData& prim, const PrimitivePose& pose, std::span<glm::vec3> outPositions,
                                 std::span<glm::vec3> outNormals = {});

// The clip index for `wanted`: "" (the first clip, or -1 without clips), an index
// (-1 = rest pose) or a name. The error names the model file and lists the clips:
// `no clip "Run" in fox.glb; clips are: Survey, Walk`.
Result<int> findClip(const AnimatedModel& animated, const std::string& wanted, const std::string& modelPath);

}  // namespace engine
