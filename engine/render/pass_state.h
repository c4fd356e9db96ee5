#pragma once
// A pass's fixed-function state in one struct, set whole when the pass begins
// (Filament's RenderPass, sokol's pipelines) instead of toggled here and there: a
// pass cannot inherit a stray glDisable from the one before it. Draws change only
// culling, for a double-sided material, and put it back.
#include <glad/gl.h>

namespace engine {

struct PassState {
  bool depthTest = true;
  GLenum depthFunc = GL_GREATER;  // reverse-Z colour passes; shadow maps use GL_LESS
  bool depthWrite = true;
  bool depthClamp = false;  // shadow casters in front of the light's near plane still cast
  bool cull = true;
  GLenum frontFace = GL_CCW;
  bool polygonOffset = false;
  float offsetFactor = 0.0f, offsetUnits = 0.0f;
  bool blend = false;      // "over" in the target's linear colour, the target's alpha kept
  bool zeroToOneDepth = true;  // glClipControl: reverse-Z and shadow boxes clip depth to 0..w
};

void applyPassState(const PassState& state);

// The passes of the scene renderer. Shadow maps: a slope-scaled offset (surfaces at
// grazing angles to the light get more), depth-less-than into a map cleared to 1.
inline constexpr PassState kShadowPass{.depthFunc = GL_LESS, .polygonOffset = true, .offsetFactor = 1.5f,
                                       .offsetUnits = 2.0f};
// The terrain into a sun map: as above, depth clamped.
inline constexpr PassState kTerrainShadowPass{.depthFunc = GL_LESS, .depthClamp = true, .polygonOffset = true,
                                              .offsetFactor = 1.5f, .offsetUnits = 2.0f};
// The point light's cube faces are seen from inside, where GL's cube orientation
// mirrors: both sides drawn, so no caster is lost.
inline constexpr PassState kCubeShadowPass{.depthFunc = GL_LESS, .cull = false, .polygonOffset = true,
                                           .offsetFactor = 1.5f, .offsetUnits = 2.0f};
// Opaque colour: reverse-Z. A left-handed view is a mirror, which turns
// counter-clockwise faces clockwise.
constexpr PassState opaquePassFor(bool leftHanded) {
  return PassState{.frontFace = GLenum(leftHanded ? GL_CW : GL_CCW)};
}
// The sky into a cube map: no depth, every texel.
inline constexpr PassState kSkyPass{.depthTest = false, .depthWrite = false, .cull = false};
// The sky in a view, after its opaque surfaces: sky.vert puts it on the far plane
// (depth 0 in reverse-Z, the value the depth is cleared to), so it is shaded only
// where nothing was drawn.
inline constexpr PassState kSkyBehindPass{.depthFunc = GL_GEQUAL, .depthWrite = false, .cull = false};
// The full-screen shading of a surface (the deferred terrain's, the deferred
// characters'), where the stencil marks it.
inline constexpr PassState kSurfaceShadingPass{.depthTest = false, .depthWrite = false, .cull = false};
// The same where no stencil marks it: over whatever depth was drawn (the far
// plane's full-screen triangle passes in front of nothing else).
inline constexpr PassState kSurfaceDepthShadingPass{.depthFunc = GL_LESS, .depthWrite = false, .cull = false};
// BLEND materials after the opaque ones: tested against their depth, writing none.
constexpr PassState blendPassFor(bool leftHanded) {
  return PassState{.depthWrite = false, .frontFace = GLenum(leftHanded ? GL_CW : GL_CCW), .blend = true};
}
// Tone mapping into the caller's framebuffer.
inline constexpr PassState kPostPass{.depthTest = false, .depthFunc = GL_LESS, .cull = false,
                                     .zeroToOneDepth = false};
// What a frame leaves for the caller (a UI drawn over it, the viewer): GL's usual
// depth test and clip space, back faces culled.
inline constexpr PassState kCallerState{.depthFunc = GL_LESS, .zeroToOneDepth = false};

}  // namespace engine
