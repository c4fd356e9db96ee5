#pragma once
// The deferred characters' groups (render/character_surface_pass.h): the opaque
// primitives that share an asset, a material and a shading program, each shaded from
// the surface by one full-screen pass. SceneDraws fills them while it builds its
// programs and reads them when it collects and draws the characters' surface; the
// pass shades by them. Their own file, so that neither of the two includes the
// other. Not part of the engine's interface.
#include <cstddef>
#include <vector>

#include "render/model_renderer.h"

namespace engine {

struct CharacterAsset;

class SurfaceGroups {
 public:
  struct Group {
    const CharacterAsset* asset = nullptr;
    int material = -1;
    ShaderVariant shading;  // ShaderVariant::shadingFromSurface of its primitives
  };

  // `terrainStencil`: the deferred terrain marks its pixels in the same stencil.
  explicit SurfaceGroups(bool terrainStencil) : terrainStencil_(terrainStencil) {}

  // At load: the primitives of `asset` with `material`, whose forward variant is
  // `forward`, are shaded from the surface by one pass.
  void add(const CharacterAsset& asset, int material, const ShaderVariant& forward);
  int groupOf(const CharacterAsset& asset, int material, const ShaderVariant& forward) const;  // -1: none
  // Once every group is added: whether there is work (none past kMaxSurfaceGroups,
  // which the stencil cannot tell apart; then the groups are emptied), and then the
  // programs drawn with appended to `variants` (the surface variants of the
  // primitives the groups take are `surfaceVariants`).
  bool finish(const std::vector<ShaderVariant>& surfaceVariants, std::vector<ShaderVariant>& variants);
  // Which pixels a group holds: its stencil value where groups share the frame with
  // each other or the terrain's surface; else any depth drawn before the other
  // opaque draws (the surfaces come first).
  bool stencil() const { return terrainStencil_ || groups_.size() > 1; }
  const std::vector<Group>& groups() const { return groups_; }
  std::size_t size() const { return groups_.size(); }
  bool empty() const { return groups_.empty(); }

 private:
  bool terrainStencil_;
  std::vector<Group> groups_;  // each with its stencil value, in order
};

}  // namespace engine
