#pragma once
// The physically based path tracer (demo --mode pathtrace): the ground truth that the
// rasterizer's shortcuts and the course's Whitted tracer are measured against. It
// shares the scene (RtScene), the camera, the BVH and the material models
// (core/brdf.h through bsdf.h) with the Whitted tracer, and nothing of its
// approximations: no ambient term, all bounces of indirect light.
//
// At every hit: the surface's emission, then next-event estimation to every light (a
// shadow ray each: the sun as a delta or a cone of its angular size, points, area
// rectangles, the environment by importance), then one BSDF sample to continue the
// path. Light and BSDF samples of the same light are combined by multiple importance
// sampling with the power heuristic; deltas (point lights, a sun of angle 0, mirrors)
// take their one strategy whole. Russian roulette after `rouletteDepth` bounces.
//
// Radiometry, in the engine's convention that a light's colour * intensity I is what a
// white Lambert surface facing it reflects: a sun gives irradiance pi I (a cone sun
// has radiance I / sin^2 of its half angle), a point light pi I / d^2 with fall-off
// (pi I without, as the course's lights), an area light emits radiance I from the
// side its edges u x v face (so a surface under a light that fills its sky reflects
// albedo * I, as under the course's unattenuated lights). Area lights are emitters,
// not occluders: a ray passes through them, as shadow rays always have.
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/integrator.h"
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
  glm::vec3 direction{0.0f, 1.0f, 0.0f};
  float cosMax = 1.0f;
  glm::vec3 radiance{0.0f};
  // Point and area: the position (area: the centre), edges, unit normal and area.
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

RenderResult renderPathTraced(const RtScene& scene, const PathLights& lights, const RenderSettings& settings);
// pathTracePixel of pixels x0 .. x1 - 1 of row y into out[0 ..], their paths traced
// side by side as render() traces them (the same colours).
void pathTraceSpan(const RtScene& scene, const PathLights& lights, const RenderSettings& settings, int x0, int x1,
                   int y, glm::vec3* out, RayCounters& counters);
glm::vec3 pathTracePixel(const RtScene& scene, const PathLights& lights, const RenderSettings& settings, int x, int y,
                         RayCounters& counters);
// The radiance arriving along `ray` (as seen by a camera ray: emitters count whole).
glm::vec3 pathTraceRay(const RtScene& scene, const PathLights& lights, const RenderSettings& settings,
                       const Ray<double>& ray, std::uint64_t seed, RayCounters& counters);

}  // namespace engine::rt
