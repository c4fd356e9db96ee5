#include "render/point_shadow_pass.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/bindings.h"
#include "render/pass_state.h"
#include "render/scene_draws.h"
#include "render/scene_view.h"

namespace engine {
namespace {

constexpr int kMaxCubeShadowSize = 1024;

}  // namespace

Result<std::unique_ptr<PointShadowPass>> PointShadowPass::create(const glm::dvec3& position, int size,
                                                                 double farPlane, SceneDraws& draws) {
  std::unique_ptr<PointShadowPass> pass(new PointShadowPass(draws));
  pass->position_ = position;
  pass->size_ = std::min(size, kMaxCubeShadowSize);
  pass->far_ = farPlane;
  const int cubeSize = pass->size_;
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
  glTextureStorage2D(id, 1, GL_DEPTH_COMPONENT32F, cubeSize, cubeSize);
  pass->map_ = gl::Texture::adopt(id, cubeSize, cubeSize);
  pass->map_.parameter(GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  pass->map_.parameter(GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  pass->map_.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  pass->map_.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  pass->fbo_ = gl::Framebuffer::create();
  // Each face is attached in turn when drawn; all six are alike, so face 0 stands
  // for them here.
  glNamedFramebufferTextureLayer(pass->fbo_.id(), GL_DEPTH_ATTACHMENT, pass->map_.id(), 0, 0);
  if (auto s = pass->fbo_.check("shadow-point"); !s) return s.error();
  return pass;
}

Status PointShadowPass::render(const glm::dvec3& cameraPosition) {
  const glm::dvec3 light = position_ - cameraPosition;
  const glm::dmat4 proj = glm::perspectiveRH_ZO(glm::half_pi<double>(), 1.0, near_, far_);
  glViewport(0, 0, size_, size_);
  applyPassState(kCubeShadowPass);
  glClearDepth(1.0);
  // One list for the six faces: nothing is culled to a face.
  auto casters = draws_.collect(nullptr, true);
  if (!casters) return casters.error();
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(fbo_.id(), GL_DEPTH_ATTACHMENT, map_.id(), 0, face);
    fbo_.bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    const glm::mat4 faceViewProjection(proj * glm::lookAt(light, light + kCubeFaceDirections[face], kCubeFaceUps[face]));
    if (auto s = draws_.draw(casters->opaque, {true, faceViewProjection, faceViewProjection}); !s) return s;
  }
  drawn_ = true;
  return Ok{};
}

void PointShadowPass::setUniforms(const gl::Program& program) const {
  program.set("u_pointNear", float(near_));
  map_.bind(gl::binding::kPointShadow);
}

std::string PointShadowPass::describe(const std::string& filter) const {
  return "shadow-point(cube " + std::to_string(size_) + ", " + filter + ")";
}

}  // namespace engine
