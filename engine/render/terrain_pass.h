#pragma once
// The scene's terrain (terrain/terrain_renderer.h) in the frame's views: each
// view's CDLOD selection, less the patches an opaque plane hides, drawn after the
// view's opaque draws. The main view's terrain, without MSAA, is shaded once a
// pixel from the surface it leaves (beginSurface). The sun's maps draw it through
// select and renderer(); GPU culling draws the main view's in parts. Not part of
// the engine's interface.
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "render/plane_occlusion.h"
#include "render/scene_view.h"
#include "scene/terrain_mesh.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain/terrain_renderer.h"

namespace engine {

class GpuScene;
class SceneDraws;
struct SceneStats;

struct TerrainPassSettings {
  double errorPixels = 2.0;  // the LOD target (terrain.error_pixels or the override)
  bool deferred = false;     // shaded once a pixel in the main view
  // Terrain patches hidden by opaque planes are left out (render/plane_occlusion.h);
  // tests only turn it off or change its margin.
  bool planeOcclusion = true;
  double planeOcclusionPixelMargin = cull::kPlanePixelMargin;
};

class TerrainPass {
 public:
  // The colour programs are the scene programs' variant (`defines`): the terrain is
  // lit and shadowed as they are.
  static Result<std::unique_ptr<TerrainPass>> create(const std::string& shaderDir, terrain::Terrain& terrain,
                                                     const std::vector<std::string>& defines,
                                                     const TerrainPassSettings& settings, const SceneDesc& scene,
                                                     const GpuScene& gpu, const SceneDraws& draws, SceneStats* stats);

  const terrain::Terrain& terrain() const { return terrain_; }
  terrain::TerrainRenderer& renderer() { return *renderer_; }
  bool deferred() const { return settings_.deferred; }
  // The surface's target, attached to the frame's framebuffer of width x height
  // (deferred only).
  void attach(gl::Framebuffer& target, int width, int height);

  // Every block error the view from the eye needs, before any of the frame's
  // selections.
  void measure(double fovy, int viewportHeight);
  // The view camera's LOD, culled against `cullViewProjection`.
  terrain::LodSelection select(const glm::mat4& cullViewProjection, double fovy, int viewportHeight) const;
  void hidePatchesBehindPlanes(terrain::LodSelection& selection, const View& view, int skipShape) const;
  // A view's terrain, after its opaque draws (`skipShape`: a probe's own mirror,
  // not drawn); `target`: the main view's framebuffer, which holds the surface.
  void draw(const View& view, int skipShape, const gl::Framebuffer& target);
  // What the terrain's draws write in `view`: the surface (the stencil then marks
  // it), or the colour.
  terrain::TerrainOutput beginSurface(const View& view, const gl::Framebuffer& target);
  // After beginSurface's draws: the shading where the stencil marks terrain.
  void shadeSurface(const View& view, const terrain::LodSelection& selection, const gl::Framebuffer& target);
  // The patches the last main view drew (SceneRenderer::mainTerrainSelection).
  const terrain::LodSelection& mainSelection() const { return mainSelection_; }
  void keepMainSelection(terrain::LodSelection selection) { mainSelection_ = std::move(selection); }
  std::string describe() const;

 private:
  TerrainPass(terrain::Terrain& terrain, const TerrainPassSettings& settings, const SceneDesc& scene,
              const GpuScene& gpu, const SceneDraws& draws, SceneStats* stats)
      : terrain_(terrain), settings_(settings), scene_(scene), gpu_(gpu), draws_(draws), stats_(stats) {}
  TerrainView terrainView(double fovy, int viewportHeight) const;

  terrain::Terrain& terrain_;
  TerrainPassSettings settings_;
  const SceneDesc& scene_;
  const GpuScene& gpu_;
  const SceneDraws& draws_;
  SceneStats* stats_;
  std::unique_ptr<terrain::TerrainRenderer> renderer_;
  gl::Texture surface_;
  terrain::LodSelection mainSelection_;
};

}  // namespace engine
