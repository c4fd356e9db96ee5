#pragma once
// What the path tracer (path_tracer.h) and the GPU's (gputrace/path_kernel.cpp)
// sample for next-event estimation, prepared once a render: the scene's lights in
// the form they are sampled in, and the environment as an infinite light with an
// importance distribution over its sky.
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/rt_scene.h"
#include "raytrace/sampling.h"

namespace engine::rt {

// The environment as an infinite light: its radiance tabulated on a lat-long grid
// (Environment's convention, at Environment::resolution() for the scene's sky)
// (cell luminance times the cell's solid angle) for a piecewise-constant 2D
// importance distribution, so a sky with a bright region gets the shadow rays there.
class EnvironmentLight {
 public:
  using RadianceFn = std::function<glm::vec3(const glm::vec3&)>;
  EnvironmentLight() = default;  // black
  EnvironmentLight(RadianceFn radiance, glm::ivec2 resolution);

  glm::vec3 radiance(const glm::vec3& dir) const { return radiance_ ? radiance_(dir) : glm::vec3(0.0f); }
  // A unit direction and its solid-angle density.
  glm::vec3 sample(glm::vec2 u, float* pdf) const;
  float pdf(const glm::vec3& dir) const;
  bool black() const { return black_; }
  // Over the lat-long grid (uv, not solid angle); empty when black.
  const Distribution2D& distribution() const { return distribution_; }

 private:
  RadianceFn radiance_;
  Distribution2D distribution_;
  bool black_ = true;
};

// One light as the path tracer sees it: what it emits and how it is sampled.
struct PathLight {
  LightType type = LightType::Sun;
  glm::vec3 power{0.0f};  // colour * intensity
  bool shadows = true;
  bool falloff = false;
  // Sun: unit direction toward it; a cone when cosMax < 1, with radiance `radiance`.
  // Spot: its axis toward it.
  glm::vec3 direction{0.0f, 1.0f, 0.0f};
  float cosMax = 1.0f;
  // Point and spot: the cone's cosines (scene/environment.h's LightCone; a point's
  // holds every direction).
  float cosOuter = -3.0f, cosInner = -2.0f;
  glm::vec3 radiance{0.0f};
  // Point, spot and area: the position (area: the centre), edges, unit normal and area.
  glm::dvec3 position{0.0}, edgeU{0.0}, edgeV{0.0};
  glm::vec3 normal{0.0f, -1.0f, 0.0f};
  float area = 0.0f;
};

// What a path-traced render of one scene precomputes, once: the lights in the form
// they are sampled in and the environment's distribution; shared by every pixel,
// pass and thread.
struct PathLights {
  std::vector<PathLight> lights;
  bool coneSun = false;  // a sun of non-zero angle, seen by rays as a disk of its own
  EnvironmentLight environment;
};
std::shared_ptr<const PathLights> preparePathLights(const RtScene& scene);

}  // namespace engine::rt
