#include "render/frame_uniforms.h"

#include "gl/bindings.h"
#include "render/ibl.h"
#include "render/point_shadow_pass.h"
#include "render/sun_shadow_pass.h"

namespace engine {

CompiledLights compileLights(const SceneDesc& scene) {
  CompiledLights lights;
  for (int i = 0; i < int(scene.lights.size()); ++i) {
    const LightDesc& l = scene.lights[size_t(i)];
    if (l.type == LightType::Sun && lights.sun < 0) lights.sun = i;
    // Area lights are drawn as a point at their centre; their soft shadow is the
    // ray tracer's job (PCF only imitates it).
    if (l.type != LightType::Sun && int(lights.points.size()) < kMaxPointLights) lights.points.push_back(i);
  }
  return lights;
}

FrameUniforms::FrameUniforms(const SceneDesc& scene, CompiledLights lights, int pcfRadius, const SunShadowPass* sun,
                             const PointShadowPass* point, const EnvironmentLighting* environment)
    : scene_(scene),
      lights_(std::move(lights)),
      pcfRadius_(pcfRadius),
      sun_(sun),
      point_(point),
      environment_(environment),
      ubo_(gl::Buffer::create(sizeof(FrameBlock))) {}

void FrameUniforms::fill(const glm::dvec3& eye, const glm::mat4& viewProjection) {
  FrameBlock& frame = block_;
  frame.viewProjection = viewProjection;
  frame.sunDirection = glm::vec4(0.0f);
  if (lights_.sun >= 0) {
    const LightDesc& sun = scene_.lights[size_t(lights_.sun)];
    frame.sunDirection = glm::vec4(glm::vec3(sun.direction), 1.0f);
    frame.sunColor = glm::vec4(sun.color * sun.intensity, 0.0f);
  }
  if (sun_) sun_->fill(frame);
  frame.counts = glm::ivec4(int(lights_.points.size()), 0, 0, 0);
  for (size_t i = 0; i < lights_.points.size(); ++i) {
    const LightDesc& l = scene_.lights[size_t(lights_.points[i])];
    frame.pointPosition[i] = glm::vec4(glm::vec3(l.position - eye), l.falloff ? 1.0f : 0.0f);
    frame.pointColor[i] = glm::vec4(l.color * l.intensity, l.shadows ? 1.0f : 0.0f);
  }
  // Ambient from the sky: the zenith and ground colours, dimmed.
  frame.ambientSky = glm::vec4(ambientSkyColor(scene_), scene_.ambient);
  frame.ambientGround = glm::vec4(ambientGroundColor(scene_), 0.0f);
  frame.fog = scene_.fog.enabled ? glm::vec4(scene_.fog.color, scene_.fog.density) : glm::vec4(0.0f);
  // Without a point shadow no shader reads its far plane: the block keeps the
  // value it has always had there.
  const double pointFar = point_ ? point_->farPlane() : 50.0;
  frame.shadowParams = glm::vec4(sun_ ? 1.0f / float(sun_->size()) : 0.0f, float(pcfRadius_), float(pointFar),
                                 point_ ? 2.0f / float(point_->size()) : 0.0f);
  if (environment_) {
    for (int i = 0; i < 9; ++i) frame.shIrradiance[i] = glm::vec4(environment_->sh().coefficients[size_t(i)], 0.0f);
    frame.iblParams = glm::vec4(float(environment_->maxLevel()), 0.0f, 0.0f, 0.0f);
    environment_->bind();
  }
  ubo_.upload(0, sizeof(FrameBlock), &frame);
  bind();
}

void FrameUniforms::bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, ubo_.id()); }

}  // namespace engine
