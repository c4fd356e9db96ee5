#include "render/character_surface_pass.h"

#include <sstream>

#include "gl/bindings.h"
#include "render/character.h"
#include "render/gpu_scene.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/scene_stats.h"
#include "render/screen_rect.h"

namespace engine {

void CharacterSurfacePass::attach(gl::Framebuffer& target, int width, int height) {
  surface_ = gl::Texture::create2D(GL_RGBA32UI, width, height, 1);
  surface_.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // an integer texture filters nothing
  surface_.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  target.attach(GL_COLOR_ATTACHMENT2, surface_);
  if (!position_) return;
  distance_ = gl::Texture::create2D(GL_R32F, width, height, 1);
  target.attach(GL_COLOR_ATTACHMENT3, distance_);
}

Status CharacterSurfacePass::draw(const View& view, const std::vector<DrawItem>& items, const PassInputs& pass,
                                  const ItemCommands* commands, const gl::Framebuffer& target) {
  if (items.empty()) return Ok{};
  const GLenum surfaceOnly[] = {GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};  // common/surface.glsl's outputs
  glNamedFramebufferDrawBuffers(target.id(), position_ ? 2 : 1, surfaceOnly);
  if (stencil()) {
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);  // the item's group (SceneDraws::draw)
  }
  PassInputs surfacePass = pass;
  surfacePass.surface = true;
  Status status = draws_.draw(items, surfacePass, commands);
  const GLenum colourOnly[] = {GL_COLOR_ATTACHMENT0};
  glNamedFramebufferDrawBuffers(target.id(), 1, colourOnly);
  if (status) status = shade(view, items);
  glDisable(GL_STENCIL_TEST);
  applyPassState(opaquePassFor(view.mirrored));
  return status;
}

// One full-screen pass for each group that `items` drew, where the stencil holds
// its value; or, with one group, wherever depth was drawn: sky.vert's triangle
// lies on the far plane, depth 0 in reverse-Z, less than any surface's.
Status CharacterSurfacePass::shade(const View& view, const std::vector<DrawItem>& items) {
  std::vector<char> drawn(groups_.size(), 0);
  // Only where the drawn characters can be: llvmpipe runs a full-screen
  // triangle's fragment shader for every block of the screen, to fail its test.
  glm::ivec4 rect(view.width, view.height, 0, 0);
  for (const DrawItem& item : items) {
    drawn[size_t(item.surfaceGroup)] = 1;
    const auto [center, radius] = gpu_.placedSphere(gpu_.characters()[size_t(item.object)]);
    const glm::ivec4 r = sphereScreenRect(view.viewProjection, center, radius, view.width, view.height);
    rect = glm::ivec4(glm::min(glm::ivec2(rect), glm::ivec2(r)), glm::max(glm::ivec2(rect.z, rect.w), glm::ivec2(r.z, r.w)));
  }
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x, rect.y, rect.z - rect.x, rect.w - rect.y);
  const bool stencilled = stencil();
  applyPassState(stencilled ? kSurfaceShadingPass : kSurfaceDepthShadingPass);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  surface_.bind(gl::binding::kCharacterSurface);
  if (position_) distance_.bind(gl::binding::kCharacterDistance);
  emptyVao_.bind();
  const glm::mat4 inverseViewProjection(glm::inverse(view.viewProjection));
  Status status = Ok{};
  for (std::size_t g = 0; g < groups_.size() && status; ++g) {
    if (!drawn[g]) continue;
    const SurfaceGroups::Group& group = groups_.groups()[g];
    if (stencilled) glStencilFunc(GL_EQUAL, kFirstSurfaceStencil + int(g), 0xff);
    status = shadeModelSurface(draws_.variants(), group.asset->model, group.asset->gpu, group.material, group.shading,
                               [this](const gl::Program& p) { draws_.setUniforms(p); }, inverseViewProjection);
    ++stats_->drawCalls;
  }
  glDisable(GL_SCISSOR_TEST);
  return status;
}

// "characters(deferred: RGBA32UI surface + R32F distance + stencil, shaded once a
// pixel by 1 full-screen pass)".
std::string CharacterSurfacePass::describe() const {
  std::ostringstream out;
  out << "characters(deferred: RGBA32UI surface" << (position_ ? " + R32F distance" : "")
      << (stencil() ? " + stencil" : "") << ", shaded once a pixel by " << groups_.size() << " full-screen pass"
      << (groups_.size() == 1 ? "" : "es") << ")";
  return out.str();
}

}  // namespace engine
