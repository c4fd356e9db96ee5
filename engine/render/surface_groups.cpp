#include "render/surface_groups.h"

#include "render/scene_view.h"

namespace engine {

void SurfaceGroups::add(const CharacterAsset& asset, int material, const ShaderVariant& forward) {
  if (groupOf(asset, material, forward) < 0) groups_.push_back({&asset, material, forward.shadingFromSurface()});
}

int SurfaceGroups::groupOf(const CharacterAsset& asset, int material, const ShaderVariant& forward) const {
  const ShaderVariant shading = forward.shadingFromSurface();
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const Group& group = groups_[g];
    if (group.asset == &asset && group.material == material && group.shading == shading) return int(g);
  }
  return -1;
}

bool SurfaceGroups::finish(const std::vector<ShaderVariant>& surfaceVariants, std::vector<ShaderVariant>& variants) {
  if (groups_.size() > kMaxSurfaceGroups) groups_.clear();
  if (groups_.empty()) return false;
  variants.insert(variants.end(), surfaceVariants.begin(), surfaceVariants.end());
  for (const Group& g : groups_) variants.push_back(g.shading);
  return true;
}

}  // namespace engine
