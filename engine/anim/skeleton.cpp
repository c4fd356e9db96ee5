#include "anim/skeleton.h"

namespace engine {

Result<Skeleton> Skeleton::build(const RawSkeleton& raw) {
  std::size_t count = raw.parents.size();
  if (raw.restPose.size() != count)
    return makeError("skeleton: " + std::to_string(raw.restPose.size()) + " rest transforms for " +
                     std::to_string(count) + " joints");
  if (!raw.names.empty() && raw.names.size() != count)
    return makeError("skeleton: names must be empty or one per joint");
  std::vector<std::vector<int>> children(count);
  std::vector<int> roots;
  for (std::size_t i = 0; i < count; ++i) {
    int p = raw.parents[i];
    if (p == -1) {
      roots.push_back(static_cast<int>(i));
    } else if (p < 0 || static_cast<std::size_t>(p) >= count || static_cast<std::size_t>(p) == i) {
      return makeError("skeleton: joint " + std::to_string(i) + " has invalid parent " + std::to_string(p));
    } else {
      children[static_cast<std::size_t>(p)].push_back(static_cast<int>(i));
    }
  }

  Skeleton s;
  s.jointOfRaw_.assign(count, -1);
  s.rawOfJoint_.reserve(count);
  // Depth first with an explicit stack (a 100k-joint chain must not overflow the
  // call stack). Children are pushed in reverse so they come out in file order.
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    int rawIndex = stack.back();
    stack.pop_back();
    s.jointOfRaw_[static_cast<std::size_t>(rawIndex)] = static_cast<int>(s.rawOfJoint_.size());
    s.rawOfJoint_.push_back(rawIndex);
    const auto& kids = children[static_cast<std::size_t>(rawIndex)];
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back(*it);
  }
  if (s.rawOfJoint_.size() != count) return makeError("skeleton: the joint tree has a cycle");

  s.parents_.resize(count);
  s.restPose_.resize(count);
  s.names_.resize(count);
  for (std::size_t j = 0; j < count; ++j) {
    std::size_t r = static_cast<std::size_t>(s.rawOfJoint_[j]);
    int p = raw.parents[r];
    s.parents_[j] = p < 0 ? -1 : s.jointOfRaw_[static_cast<std::size_t>(p)];
    s.restPose_[j] = raw.restPose[r];
    if (!raw.names.empty()) s.names_[j] = raw.names[r];
  }
  return s;
}

}  // namespace engine
