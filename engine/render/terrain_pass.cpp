#include "render/terrain_pass.h"

#include <sstream>

#include "gl/bindings.h"
#include "render/gpu_scene.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/scene_stats.h"
#include "render/terrain_cull.h"

namespace engine {

Result<std::unique_ptr<TerrainPass>> TerrainPass::create(const std::string& shaderDir, terrain::Terrain& terrain,
                                                         const std::vector<std::string>& defines,
                                                         const TerrainPassSettings& settings, const SceneDesc& scene,
                                                         const GpuScene& gpu, const SceneDraws& draws,
                                                         SceneStats* stats) {
  std::unique_ptr<TerrainPass> pass(new TerrainPass(terrain, settings, scene, gpu, draws, stats));
  auto renderer = terrain::TerrainRenderer::create(shaderDir, terrain, defines);
  if (!renderer) return renderer.error();
  pass->renderer_ = std::make_unique<terrain::TerrainRenderer>(std::move(renderer).value());
  if (settings.deferred) {
    if (auto s = pass->renderer_->enableDeferred(shaderDir, defines); !s) return s.error();
  }
  return pass;
}

void TerrainPass::attach(gl::Framebuffer& target, int width, int height) {
  surface_ = gl::Texture::create2D(GL_RGBA32F, width, height, 1);
  target.attach(GL_COLOR_ATTACHMENT1, surface_);
}

// The scene layer's terrain view (scene/terrain_mesh.h) from the eye: the tracers
// select theirs through the same function with the same target and page budget.
TerrainView TerrainPass::terrainView(double fovy, int viewportHeight) const {
  TerrainView v;
  v.eye = gpu_.eye();
  v.fovY = fovy;
  v.viewportHeight = viewportHeight;
  v.errorPixels = settings_.errorPixels;
  v.maxPages = std::size_t(renderer_->pageSlots());
  return v;
}

// They all see the same errors, so the sun's maps keep the view's ranges; and a
// frame's image depends on its camera alone, not on which frames came before (a
// window and an offscreen run of another length give the same bytes). A new view
// pays about 2 ms a block, once.
void TerrainPass::measure(double fovy, int viewportHeight) {
  stats_->terrainBlocksPending = int(measureTerrain(terrain_, terrainView(fovy, viewportHeight)));
  stats_->terrainViewportHeight = viewportHeight;
}

// Its position, field of view and viewport fix every patch's level and morph;
// coarsened if it would need more height pages than the GPU pool holds.
terrain::LodSelection TerrainPass::select(const glm::mat4& cullViewProjection, double fovy,
                                          int viewportHeight) const {
  TerrainView v = terrainView(fovy, viewportHeight);
  v.cullViewProjection = cullViewProjection;
  v.zeroToOneDepth = true;  // reverse-Z and the sun's box both clip depth to 0..w
  return selectTerrain(terrain_, v);
}

// The selection's patches that one of the view's opaque planes hides wholly
// (render/plane_occlusion.h), left out: the image is the same, less the cost of
// rasterizing what would fail the depth test everywhere. `skipShape` (a probe's
// own mirror) is not drawn in the view, so it hides nothing.
void TerrainPass::hidePatchesBehindPlanes(terrain::LodSelection& selection, const View& view, int skipShape) const {
  if (!settings_.planeOcclusion) return;
  const glm::dvec2 viewport(view.width, view.height);
  const auto quads = cull::opaquePlanes(scene_, gpu_.eye(), view.viewProjection, viewport, skipShape);
  stats_->terrainPatchesHidden += int(removeHiddenPatches(terrain_, selection, quads, view.viewProjection, viewport,
                                                          settings_.planeOcclusionPixelMargin));
}

void TerrainPass::draw(const View& view, int skipShape, const gl::Framebuffer& target) {
  auto selection = select(glm::mat4(view.viewProjection), view.fovy, view.height);
  hidePatchesBehindPlanes(selection, view, skipShape);
  const terrain::TerrainOutput output = beginSurface(view, target);
  const auto drawn =
      renderer_->draw(selection, gpu_.eye(), [this](const gl::Program& p) { draws_.setUniforms(p); }, output);
  stats_->drawCalls += 1;
  stats_->terrainTriangles = int(drawn.trianglesDrawn);
  shadeSurface(view, selection, target);
  if (view.main) mainSelection_ = std::move(selection);
}

// The main view's terrain, without MSAA, is shaded once a pixel: llvmpipe shades
// eight lanes at a time, and the far patches' triangles cover a pixel or two each,
// so shading where they are drawn pays several times a pixel (about 12 ms of
// demo.json's frame). Their surface goes into the target's second attachment
// instead, where the terrain is nearest so far, marked in the stencil; shadeSurface
// then shades those pixels with the same lighting. Texture levels of detail come
// from the surface pass, where each triangle's own derivatives are known.
terrain::TerrainOutput TerrainPass::beginSurface(const View& view, const gl::Framebuffer& target) {
  if (!settings_.deferred || !view.main) return terrain::TerrainOutput::Colour;
  const GLenum surfaceOnly[] = {GL_COLOR_ATTACHMENT1};  // terrain.frag's output 0
  glNamedFramebufferDrawBuffers(target.id(), 1, surfaceOnly);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, kTerrainStencil, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  return terrain::TerrainOutput::Surface;
}

// A full-screen pass; a no-op where the terrain was shaded where drawn.
void TerrainPass::shadeSurface(const View& view, const terrain::LodSelection& selection,
                               const gl::Framebuffer& target) {
  if (!settings_.deferred || !view.main) return;
  const GLenum colourOnly[] = {GL_COLOR_ATTACHMENT0};
  glNamedFramebufferDrawBuffers(target.id(), 1, colourOnly);
  applyPassState(kSurfaceShadingPass);
  glStencilFunc(GL_EQUAL, kTerrainStencil, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  renderer_->shadeDeferred(selection, gpu_.eye(), glm::mat4(glm::inverse(view.viewProjection)),
                           [this](const gl::Program& p) {
                             draws_.setUniforms(p);
                             surface_.bind(gl::binding::kTerrainSurface);
                           });
  stats_->drawCalls += 1;
  glDisable(GL_STENCIL_TEST);
}

// "terrain(cdlod, 2 px, deferred: RGBA32F surface + stencil, shaded once a pixel)".
std::string TerrainPass::describe() const {
  std::ostringstream out;
  out << "terrain(cdlod, " << settings_.errorPixels << " px, "
      << (settings_.deferred ? "deferred: RGBA32F surface + stencil, shaded once a pixel" : "forward") << ")";
  return out.str();
}

}  // namespace engine
