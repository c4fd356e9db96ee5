#pragma once
// Turns a loaded glTF model into runtime animation data: every node becomes a
// joint of one Skeleton (so non-joint animated nodes move too), each glTF
// animation a Clip, each glTF skin a Skin of runtime joint indices.
#include <vector>

#include "anim/clip.h"
#include "anim/skeleton.h"
#include "asset/model_data.h"
#include "core/result.h"

namespace engine {

struct AnimatedModel {
  Skeleton skeleton;          // joint j is glTF node skeleton.rawOfJoint(j)
  std::vector<Clip> clips;    // one per glTF animation, same order
  std::vector<Skin> skins;    // one per glTF skin, same order
};

RawSkeleton makeRawSkeleton(const ModelData& model);
RawClip makeRawClip(const AnimationData& animation);
Result<AnimatedModel> buildAnimatedModel(const ModelData& model);

}  // namespace engine
