#pragma once
// The deferred characters: their opaque primitives shaded once a pixel. Fifty
// CesiumMan at 1280x720 draw 116,000 front faces over 83,000 pixels: most triangles
// cover a pixel or two, and llvmpipe shades a block of pixels for each, so shading
// where they are drawn pays for several lanes a pixel. Their surface
// (common/surface.glsl) goes into the frame target's colour attachment 2 instead
// (3: the distance, with positions), where each is nearest; then one full-screen
// pass per group of primitives that share a material shades those pixels, with
// the same program text (scene.frag) and so the same bytes, to rounding. Without
// MSAA, in the main view. Not part of the engine's interface.
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "render/scene_view.h"

namespace engine {

class GpuScene;
class SceneDraws;
struct CharacterAsset;
struct SceneStats;

class CharacterSurfacePass {
 public:
  // `position`: the lighting reads positions (SURFACE_POSITION), so the surface
  // keeps each pixel's distance. `terrainStencil`: the deferred terrain marks its
  // pixels in the same stencil.
  CharacterSurfacePass(bool position, bool terrainStencil, const GpuScene& gpu, SceneDraws& draws, SceneStats* stats)
      : position_(position), terrainStencil_(terrainStencil), gpu_(gpu), draws_(draws), stats_(stats) {}

  // At load: the primitives of `asset` with `material`, whose forward variant is
  // `forward`, are shaded from the surface by one pass.
  void addGroup(const CharacterAsset& asset, int material, const ShaderVariant& forward);
  int groupOf(const CharacterAsset& asset, int material, const ShaderVariant& forward) const;  // -1: none
  // Once every group is added: whether the pass has work, and a stencil value for
  // each group (else the characters are shaded where drawn). Appends the programs
  // it draws with to `variants` (the surface variants of the primitives it takes
  // are `surfaceVariants`).
  bool finishGroups(const std::vector<ShaderVariant>& surfaceVariants, std::vector<ShaderVariant>& variants);
  // Which pixels a group holds: its stencil value where groups share the frame with
  // each other or the terrain's surface; else any depth drawn before the other
  // opaque draws (the surfaces come first).
  bool stencil() const { return terrainStencil_ || groups_.size() > 1; }
  bool position() const { return position_; }
  // The surface's targets, attached to the frame's framebuffer of width x height.
  void attach(gl::Framebuffer& target, int width, int height);

  // The main view's deferrable character primitives, before its other opaque
  // draws, into `target`: their surface, then its shading. Leaves the colour
  // attachment the one drawn to, the stencil test off and the opaque pass's state.
  Status draw(const View& view, const std::vector<DrawItem>& items, const PassInputs& pass,
              const ItemCommands* commands, const gl::Framebuffer& target);
  std::string describe() const;

 private:
  struct Group {
    const CharacterAsset* asset = nullptr;
    int material = -1;
    ShaderVariant shading;  // ShaderVariant::shadingFromSurface of its primitives
  };
  Status shade(const View& view, const std::vector<DrawItem>& items);

  bool position_, terrainStencil_;
  const GpuScene& gpu_;
  SceneDraws& draws_;
  SceneStats* stats_;
  std::vector<Group> groups_;  // each with its stencil value, in order
  gl::Texture surface_, distance_;
  gl::VertexArray emptyVao_ = gl::VertexArray::create();
};

}  // namespace engine
