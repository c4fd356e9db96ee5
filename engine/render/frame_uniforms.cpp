#include "render/frame_uniforms.h"

#include <algorithm>

#include "gl/bindings.h"
#include "render/ibl.h"
#include "render/point_shadow_pass.h"
#include "render/sun_shadow_pass.h"

namespace engine {

CompiledLights compileLights(std::span<const LightDesc> lights) {
  CompiledLights out;
  std::vector<LightDesc> suns;
  for (const LightDesc& l : lights) {
    if (l.type != LightType::Sun) {
      out.others.push_back(l);
    } else if (!out.sun) {
      out.sun = l;
    } else {
      suns.push_back(l);
    }
  }
  out.others.insert(out.others.end(), suns.begin(), suns.end());
  if (int(out.others.size()) > kMaxPointLights) {
    out.dropped = int(out.others.size()) - kMaxPointLights;
    out.others.resize(size_t(kMaxPointLights));
  }
  for (const LightDesc& l : out.others) out.cones.push_back(lightCone(l));
  return out;
}

bool CompiledLights::spots() const {
  return std::any_of(others.begin(), others.end(), [](const LightDesc& l) { return l.type == LightType::Spot; });
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
  frame.u_viewProjection = viewProjection;
  frame.u_sunDirection = glm::vec4(0.0f);
  if (const auto& sun = lights_.sun) {
    frame.u_sunDirection = glm::vec4(glm::vec3(sun->direction), 1.0f);
    frame.u_sunColor = glm::vec4(sun->color * sun->intensity * sunTransmittance_, 0.0f);
  }
  if (sun_) sun_->fill(frame);
  frame.u_counts = glm::ivec4(int(lights_.others.size()), 0, 0, 0);
  for (size_t i = 0; i < lights_.others.size(); ++i) {
    const LightDesc& l = lights_.others[i];
    // w: 0 a point without falloff, 1 with 1/d^2, 2 a direction toward a sun
    // (common/frame.glsl).
    frame.u_pointPosition[i] = l.type == LightType::Sun
                                   ? glm::vec4(glm::vec3(l.direction), 2.0f)
                                   : glm::vec4(glm::vec3(l.position - eye), l.falloff ? 1.0f : 0.0f);
    frame.u_pointColor[i] = glm::vec4(l.color * l.intensity, l.shadows && l.type != LightType::Sun ? 1.0f : 0.0f);
    const LightCone& cone = lights_.cones[i];
    frame.u_pointAxis[i] = glm::vec4(cone.axisToLight, cone.cosOuter);
    frame.u_pointInner[i] = glm::vec4(cone.cosInner, 0.0f, 0.0f, 0.0f);
  }
  // Ambient from the sky: the zenith and ground colours, dimmed.
  frame.u_ambientSky = glm::vec4(ambientSkyColor(scene_), scene_.ambient);
  frame.u_ambientGround = glm::vec4(ambientGroundColor(scene_), 0.0f);
  frame.u_fog = scene_.fog.enabled ? glm::vec4(scene_.fog.color, scene_.fog.density) : glm::vec4(0.0f);
  // Without a point shadow no shader reads its far plane: the block keeps the
  // value it has always had there.
  const double pointFar = point_ ? point_->farPlane() : 50.0;
  frame.u_shadowParams = glm::vec4(sun_ ? 1.0f / float(sun_->size()) : 0.0f, float(pcfRadius_), float(pointFar),
                                   point_ ? 2.0f / float(point_->size()) : 0.0f);
  if (environment_) {
    for (int i = 0; i < 9; ++i) frame.u_shIrradiance[i] = glm::vec4(environment_->sh().coefficients[size_t(i)], 0.0f);
    frame.u_iblParams = glm::vec4(float(environment_->maxLevel()), 0.0f, 0.0f, 0.0f);
    environment_->bind();
  }
  ubo_.upload(0, sizeof(FrameBlock), &frame);
  bind();
}

void FrameUniforms::bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, ubo_.id()); }

}  // namespace engine
