// SceneRenderer's world of one view: its opaque draws, the terrain, the sky behind
// them, then transmissive and blended draws.
#include "render/scene_renderer_impl.h"

#include "gl/bindings.h"
#include "render/lighting.h"
#include "render/pass_state.h"

namespace engine {

void SceneRenderer::Impl::drawSky(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk) {
  program.use();
  if (const gl::Texture& skyImage = gpu->skyImage()) {
    const float radians = glm::radians(scene.sky.rotationDegrees);
    program.set("u_skyIntensity", scene.sky.intensity);
    program.set("u_skyRotation", glm::vec2(std::cos(radians), std::sin(radians)));
    skyImage.bind(gl::binding::kSkyImage);
  } else {
    Lighting lighting;
    lighting.sunDirection = lights.sun >= 0 ? glm::vec3(scene.lights[size_t(lights.sun)].direction) : glm::vec3(0, -1, 0);
    lighting.sunDisk = sunDisk && lights.sun >= 0 && scene.sky.sunDisk;
    lighting.skyZenith = scene.sky.zenith;
    lighting.skyHorizon = scene.sky.horizon;
    lighting.skyGround = scene.sky.ground;
    setSkyUniforms(program, lighting);
  }
  program.set("u_inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
  emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++stats->drawCalls;
}

// The sky after the opaque surfaces, where they left the cleared far depth: shaded
// once a pixel instead of under every surface (on demo.json about half the screen),
// the same colour where it shows. Before the transmissive draws, which see it
// through their copy of the frame.
void SceneRenderer::Impl::drawSkyBehind(const View& view) {
  if (!scene.sky.enabled) return;
  applyPassState(kSkyBehindPass);
  drawSky(directOutput ? skyDisplay : sky, view.viewProjection);
}

// Everything a colour pass shows, into the bound HDR framebuffer (cleared): the
// opaque draws of the view, the terrain, the sky where neither is, the transmissive
// draws over a copy of those, then the blended ones.
Status SceneRenderer::Impl::drawWorld(const View& view, int skipShape, bool useProbes) {
  applyPassState(opaquePassFor(view.mirrored));
  auto lists = draws->collect(view.planes, false, skipShape, view.main);
  if (!lists) return lists.error();
  if (culler && view.main) return drawCulled(view, *lists, useProbes);
  const PassInputs pass{false, glm::mat4(1.0f), glm::mat4(view.viewProjection), useProbes};
  if (surfaces) {
    if (auto s = surfaces->draw(view, lists->surface, pass, nullptr, drawFbo); !s) return s;
  }
  if (auto s = draws->draw(lists->opaque, pass); !s) return s;
  // The terrain after the shapes and characters: its fragment shader (five layers,
  // two sun maps, the ambient) is the frame's dearest, and a plaza or a floor over
  // it then hides what lies beneath before it is shaded (llvmpipe, like any GPU,
  // tests depth before shading). Opaque surfaces keep the nearest depth whatever the
  // order, so the image is the same. drawCulled does the same with its patches
  // culled against the depth of what went before.
  if (terrain) {
    // What is drawn so far goes to the rasterizer now: on llvmpipe its threads then
    // shade the shapes (most of a plaza's pixels) while this thread selects the
    // terrain's patches and bins its triangles, rather than both after it.
    glFlush();
    applyPassState(opaquePassFor(view.mirrored));
    terrain->draw(view, skipShape, drawFbo);
  }
  drawSkyBehind(view);
  if (lists->refracts) {
    if (view.main) copyTransmissionSource();
    transmissionSource.bind(gl::binding::kTransmissionSource);
    applyPassState(opaquePassFor(view.mirrored));
    if (auto s = draws->draw(lists->transmissive, pass); !s) return s;
  }
  if (lists->blend.empty()) return Ok{};
  applyPassState(blendPassFor(view.mirrored));
  return draws->draw(lists->blend, pass);
}

// What the transmissive draws refract: the view's colour so far (sky, terrain and
// opaque draws; MSAA resolved by the blit), with its mip chain for rough surfaces.
void SceneRenderer::Impl::copyTransmissionSource() {
  glBlitNamedFramebuffer(drawFbo.id(), transmissionFbo.id(), 0, 0, targetWidth, targetHeight, 0, 0, targetWidth,
                         targetHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glGenerateTextureMipmap(transmissionSource.id());
}

}  // namespace engine
