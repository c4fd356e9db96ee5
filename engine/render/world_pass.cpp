#include "render/world_pass.h"

#include "render/character_surface_pass.h"
#include "render/gpu_cull_pass.h"
#include "render/output_pass.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/sky_pass.h"
#include "render/terrain_pass.h"
#include "render/transmission_pass.h"

namespace engine {

Status WorldPass::draw(const View& view, int skipShape, bool useProbes) {
  applyPassState(opaquePassFor(view.mirrored));
  auto lists = draws_.collect(view.planes, false, skipShape, view.main);
  if (!lists) return lists.error();
  if (culling_ && view.main) return drawCulled(view, *lists, useProbes);
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  if (surfaces_) {
    if (auto s = surfaces_->draw(view, lists->surface, pass, nullptr, output_.framebuffer()); !s) return s;
  }
  if (auto s = draws_.draw(lists->opaque, pass); !s) return s;
  // The terrain after the shapes and characters: its fragment shader (five layers,
  // two sun maps, the ambient) is the frame's dearest, and a plaza or a floor over
  // it then hides what lies beneath before it is shaded (llvmpipe, like any GPU,
  // tests depth before shading). Opaque surfaces keep the nearest depth whatever the
  // order, so the image is the same. drawCulled does the same with its patches
  // culled against the depth of what went before.
  if (terrain_) {
    // What is drawn so far goes to the rasterizer now: on llvmpipe its threads then
    // shade the shapes (most of a plaza's pixels) while this thread selects the
    // terrain's patches and bins its triangles, rather than both after it.
    glFlush();
    applyPassState(opaquePassFor(view.mirrored));
    terrain_->draw(view, skipShape, output_.framebuffer());
  }
  sky_.drawBehind(view);
  if (lists->refracts) {
    if (view.main) transmission_->copy(output_.framebuffer());
    transmission_->bind();
    applyPassState(opaquePassFor(view.mirrored));
    if (auto s = draws_.draw(lists->transmissive, pass); !s) return s;
  }
  if (lists->blend.empty()) return Ok{};
  applyPassState(blendPassFor(view.mirrored));
  return draws_.draw(lists->blend, pass);
}

// The main view's draws with GPU culling, in the order draw() draws them, every
// one culled before the first is drawn (GpuCullPass::cull).
Status WorldPass::drawCulled(const View& view, const DrawLists& lists, bool useProbes) {
  auto commands = culling_->cull(view, lists);
  if (!commands) return commands.error();
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  Status status = surfaces_ ? surfaces_->draw(view, lists.surface, pass, &commands->surface, output_.framebuffer())
                            : Status(Ok{});
  if (status) status = draws_.draw(lists.opaque, pass, &commands->opaque);
  // The terrain after the opaque items, as draw() draws it: its patches then meet
  // their depth (a plaza over a valley) in the pyramid of its second half.
  if (status && terrain_) {
    applyPassState(opaquePassFor(view.mirrored));
    culling_->drawTerrain(view, output_.framebuffer());
  }
  if (status) sky_.drawBehind(view);
  if (status && lists.refracts) {
    transmission_->copy(output_.framebuffer());
    transmission_->bind();
    applyPassState(opaquePassFor(view.mirrored));
    status = draws_.draw(lists.transmissive, pass, &commands->transmissive);
  }
  if (status && !lists.blend.empty()) {
    applyPassState(blendPassFor(view.mirrored));
    status = draws_.draw(lists.blend, pass, &commands->blend);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  return status;
}

}  // namespace engine
