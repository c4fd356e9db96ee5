#pragma once
// The frame block (render/frame_block.h, shaders/common/frame.glsl) that every
// scene program reads: the lights, the ambient, the fog and the shadow maps'
// parameters, filled for each view the frame draws (the camera's, a reflection
// probe's faces). Not part of the engine's interface.
#include <optional>
#include <span>
#include <vector>

#include "asset/scene_desc.h"
#include "gl/resources.h"
#include "render/frame_block.h"
#include "scene/environment.h"

namespace engine {

class EnvironmentLighting;
class PointShadowPass;
class SunShadowPass;

// The lights the scene programs have compiled in (common/direct_light.glsl says
// why their counts are), from the scene's environment (scene/environment.h): the
// sun (its first), with the shadow map; and up to kMaxPointLights others in the
// frame block's light array: the point lights and spots (the first with its cube
// shadow when it asks for one), area lights as a point at their centre (their soft shadow is the
// tracers' job), then any further sun as a directional light, unshadowed.
struct CompiledLights {
  std::optional<LightDesc> sun;
  std::vector<LightDesc> others;
  std::vector<LightCone> cones;  // others' cones, made once (scene/environment.h)
  int dropped = 0;  // past kMaxPointLights: not drawn (--describe and a warning say so)
  bool pointShadows() const { return !others.empty() && others[0].type != LightType::Sun && others[0].shadows; }
  bool spots() const;  // whether a light drawn has a cone (SPOT_LIGHTS)
};
CompiledLights compileLights(std::span<const LightDesc> lights);

class FrameUniforms {
 public:
  // The passes whose maps the block describes, where the scene has them (null
  // otherwise); `pcfRadius`: the shadows' filter.
  FrameUniforms(const SceneDesc& scene, CompiledLights lights, int pcfRadius, const SunShadowPass* sun,
                const PointShadowPass* point, const EnvironmentLighting* environment);
  const CompiledLights& lights() const { return lights_; }
  // The block for a view from `eye` (positions relative to it), uploaded and bound;
  // the sun's shadow matrices are its last render's.
  void fill(const glm::dvec3& eye, const glm::mat4& viewProjection);
  // Shadow passes use only their own light matrix, but every scene program declares
  // the block: it stays bound.
  void bind() const;
  // The sun as it reaches the scene through a planet's air (its transmittance,
  // render/atmosphere_tables.h), and turned for the time of day; 1 and the
  // light's own direction otherwise.
  void setSunTransmittance(const glm::vec3& transmittance) { sunTransmittance_ = transmittance; }
  void setSunDirection(const glm::vec3& direction) {
    if (lights_.sun) lights_.sun->direction = glm::dvec3(direction);
  }

 private:
  const SceneDesc& scene_;
  CompiledLights lights_;
  int pcfRadius_ = 0;
  const SunShadowPass* sun_;
  const PointShadowPass* point_;
  const EnvironmentLighting* environment_;
  glm::vec3 sunTransmittance_{1.0f};
  FrameBlock block_;
  gl::Buffer ubo_;
};

}  // namespace engine
