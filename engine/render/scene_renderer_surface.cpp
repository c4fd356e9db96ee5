// SceneRenderer's deferred characters. Fifty CesiumMan at 1280x720 draw 116,000
// front faces over 83,000 pixels: most triangles cover a pixel or two, and llvmpipe
// shades a block of pixels for each, so shading where they are drawn pays for
// several lanes a pixel. Their surface (common/surface.glsl) goes into drawFbo's
// colour attachment 2 instead, where each is nearest; then one full-screen pass per
// material shades those pixels, with the same program text (scene.frag) and so
// the same bytes, to rounding.
#include "render/scene_renderer_impl.h"
#include "render/screen_rect.h"

namespace engine {

// Setup: the primitives of `asset` with `material`, whose forward variant is
// `forward`, are shaded from the surface by one pass.
void SceneRenderer::Impl::addSurfaceGroup(const CharacterAsset& asset, int material, const ShaderVariant& forward) {
  if (surfaceGroupOf(asset, material, forward) < 0)
    surfaceGroups.push_back({&asset, material, forward.shadingFromSurface()});
}

int SceneRenderer::Impl::surfaceGroupOf(const CharacterAsset& asset, int material, const ShaderVariant& forward) const {
  const ShaderVariant shading = forward.shadingFromSurface();
  for (std::size_t g = 0; g < surfaceGroups.size(); ++g) {
    const SurfaceGroup& group = surfaceGroups[g];
    if (group.asset == &asset && group.material == material && group.shading == shading) return int(g);
  }
  return -1;
}

// The main view's deferrable character primitives, before its other opaque draws:
// their surface, then its shading. Leaves the colour attachment the one drawn to,
// the stencil test off and the opaque pass's state.
Status SceneRenderer::Impl::drawCharacterSurfaces(const View& view, const std::vector<DrawItem>& items,
                                                  const PassInputs& pass, const ItemCommands* commands) {
  if (items.empty()) return Ok{};
  const GLenum surfaceOnly[] = {GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};  // common/surface.glsl's outputs
  glNamedFramebufferDrawBuffers(drawFbo.id(), surfacePosition ? 2 : 1, surfaceOnly);
  if (surfaceStencil()) {
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);  // the item's group (submitItems)
  }
  PassInputs surfacePass = pass;
  surfacePass.surface = true;
  Status status = drawItems(items, surfacePass, commands);
  const GLenum colourOnly[] = {GL_COLOR_ATTACHMENT0};
  glNamedFramebufferDrawBuffers(drawFbo.id(), 1, colourOnly);
  if (status) status = shadeCharacterSurfaces(view, items);
  glDisable(GL_STENCIL_TEST);
  applyPassState(opaquePassFor(view.mirrored));
  return status;
}

// One full-screen pass for each group that `items` drew, where the stencil holds
// its value; or, with one group, wherever depth was drawn: sky.vert's triangle
// lies on the far plane, depth 0 in reverse-Z, less than any surface's.
Status SceneRenderer::Impl::shadeCharacterSurfaces(const View& view, const std::vector<DrawItem>& items) {
  std::vector<char> drawn(surfaceGroups.size(), 0);
  // Only where the drawn characters can be: llvmpipe runs a full-screen
  // triangle's fragment shader for every block of the screen, to fail its test.
  glm::ivec4 rect(targetWidth, targetHeight, 0, 0);
  for (const DrawItem& item : items) {
    drawn[size_t(item.surfaceGroup)] = 1;
    const auto [center, radius] = gpu->placedSphere(gpu->characters()[size_t(item.object)]);
    const glm::ivec4 r = sphereScreenRect(view.viewProjection, center, radius, targetWidth, targetHeight);
    rect = glm::ivec4(glm::min(glm::ivec2(rect), glm::ivec2(r)), glm::max(glm::ivec2(rect.z, rect.w), glm::ivec2(r.z, r.w)));
  }
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x, rect.y, rect.z - rect.x, rect.w - rect.y);
  const bool stencil = surfaceStencil();
  applyPassState(stencil ? kSurfaceShadingPass : kSurfaceDepthShadingPass);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  characterSurface.bind(gl::binding::kCharacterSurface);
  if (surfacePosition) characterDistance.bind(gl::binding::kCharacterDistance);
  emptyVao.bind();
  const glm::mat4 inverseViewProjection(glm::inverse(view.viewProjection));
  Status status = Ok{};
  for (std::size_t g = 0; g < surfaceGroups.size() && status; ++g) {
    if (!drawn[g]) continue;
    const SurfaceGroup& group = surfaceGroups[g];
    if (stencil) glStencilFunc(GL_EQUAL, kFirstSurfaceStencil + int(g), 0xff);
    status = shadeModelSurface(*variants, group.asset->model, group.asset->gpu, group.material, group.shading,
                               [this](const gl::Program& p) { setUniforms(p); }, inverseViewProjection);
    ++stats->drawCalls;
  }
  glDisable(GL_SCISSOR_TEST);
  return status;
}

}  // namespace engine
