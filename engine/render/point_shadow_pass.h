#pragma once
// The first point light's cube shadow map (common/shadows.glsl): every caster,
// in six faces drawn from the light. Not part of the engine's interface.
#include <memory>
#include <string>

#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"

namespace engine {

class SceneDraws;

class PointShadowPass {
 public:
  // A cube of `size` texels a face (at most 1024) around a light at
  // `position`, out to `farPlane`.
  static Result<std::unique_ptr<PointShadowPass>> create(const glm::dvec3& position, int size, double farPlane,
                                                         SceneDraws& draws);
  // The six faces, positions relative to `cameraPosition`.
  Status render(const glm::dvec3& cameraPosition);
  // Without characters nothing moves: the map (which does not depend on the
  // camera) is drawn once and kept.
  bool drawn() const { return drawn_; }
  // A scene program's point shadow uniforms and map.
  void setUniforms(const gl::Program& program) const;
  int size() const { return size_; }
  // "shadow-point(cube 1024, hard)"; `filter`: the shadows' ("pcf 3", "hard").
  std::string describe(const std::string& filter) const;
  double farPlane() const { return far_; }

 private:
  explicit PointShadowPass(SceneDraws& draws) : draws_(draws) {}

  SceneDraws& draws_;
  glm::dvec3 position_{0.0};
  int size_ = 0;
  double near_ = 0.05, far_ = 0.0;
  gl::Texture map_;
  gl::Framebuffer fbo_;
  bool drawn_ = false;
};

}  // namespace engine
