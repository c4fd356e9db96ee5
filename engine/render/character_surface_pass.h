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
#include "render/surface_groups.h"

namespace engine {

class GpuScene;
class SceneDraws;
struct SceneStats;

class CharacterSurfacePass {
 public:
  // `position`: the lighting reads positions (SURFACE_POSITION), so the surface
  // keeps each pixel's distance. `terrainStencil`: the deferred terrain marks its
  // pixels in the same stencil.
  CharacterSurfacePass(bool position, bool terrainStencil, const GpuScene& gpu, SceneDraws& draws, SceneStats* stats)
      : position_(position), groups_(terrainStencil), gpu_(gpu), draws_(draws), stats_(stats) {}

  // The groups SceneDraws fills at load (SceneDraws::buildVariants) and collects
  // the characters' surface by.
  SurfaceGroups& groups() { return groups_; }
  const SurfaceGroups& groups() const { return groups_; }
  bool stencil() const { return groups_.stencil(); }
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
  Status shade(const View& view, const std::vector<DrawItem>& items);

  bool position_;
  SurfaceGroups groups_;
  const GpuScene& gpu_;
  SceneDraws& draws_;
  SceneStats* stats_;
  gl::Texture surface_, distance_;
  gl::VertexArray emptyVao_ = gl::VertexArray::create();
};

}  // namespace engine
