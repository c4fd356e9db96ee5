#pragma once
// A joint hierarchy stored parents-before-children, so that local-to-model is one
// forward loop. Every glTF node becomes a joint: scenes can have several roots and
// animated nodes that are not skin joints must move too.
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/math.h"
#include "core/result.h"

namespace engine {

// Offline description, in any order (e.g. glTF node order).
struct RawSkeleton {
  std::vector<int> parents;  // -1 for roots
  std::vector<Srt> restPose;
  std::vector<std::string> names;  // optional: empty or one per joint
};

class Skeleton {
 public:
  // Orders the joints depth first; fails on a bad parent index or a cycle.
  static Result<Skeleton> build(const RawSkeleton& raw);

  int jointCount() const { return static_cast<int>(parents_.size()); }
  std::span<const int> parents() const { return parents_; }  // parents_[i] < i
  std::span<const Srt> restPose() const { return restPose_; }
  const std::string& name(int joint) const { return names_[static_cast<std::size_t>(joint)]; }
  // Maps between RawSkeleton indices (glTF nodes) and runtime joint indices.
  int jointOfRaw(int rawIndex) const { return jointOfRaw_[static_cast<std::size_t>(rawIndex)]; }
  int rawOfJoint(int joint) const { return rawOfJoint_[static_cast<std::size_t>(joint)]; }

 private:
  std::vector<int> parents_;
  std::vector<Srt> restPose_;
  std::vector<std::string> names_;
  std::vector<int> jointOfRaw_;
  std::vector<int> rawOfJoint_;
};

// A skin: the joints one mesh is bound to (runtime joint indices) and the inverse
// bind matrix of each; palette[k] = model[joints[k]] * inverseBinds[k].
struct Skin {
  std::vector<int> joints;
  std::vector<glm::mat4> inverseBinds;
};

}  // namespace engine
