#include "render/pass_state.h"

namespace engine {

namespace {
void enable(GLenum capability, bool on) { on ? glEnable(capability) : glDisable(capability); }
}  // namespace

void applyPassState(const PassState& state) {
  enable(GL_DEPTH_TEST, state.depthTest);
  glDepthFunc(state.depthFunc);
  glDepthMask(state.depthWrite ? GL_TRUE : GL_FALSE);
  enable(GL_DEPTH_CLAMP, state.depthClamp);
  enable(GL_CULL_FACE, state.cull);
  glFrontFace(state.frontFace);
  enable(GL_POLYGON_OFFSET_FILL, state.polygonOffset);
  glPolygonOffset(state.offsetFactor, state.offsetUnits);
  enable(GL_BLEND, state.blend);
  if (state.blend) glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glClipControl(GL_LOWER_LEFT, state.zeroToOneDepth ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
}

}  // namespace engine
