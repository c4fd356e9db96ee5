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
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "raytrace/integrator_method.h"
#include "raytrace/ray.h"
#include "raytrace/render_types.h"

namespace engine::rt {

class RtScene;
struct PathLights;

class PathIntegrator final : public IntegratorMethod {
 public:
  // Prepares the scene's lights (path_lights.h) once, for every pixel, pass and thread.
  PathIntegrator(const RtScene& scene, RenderSettings settings);

  RenderResult render() const override;
  glm::vec3 renderPixel(int x, int y, RayCounters& counters) const override;
  glm::vec3 renderPixelSamples(int x, int y, int first, int count, RayCounters& counters) const override;
  // The pixels' paths traced side by side, as render() traces a tile's row.
  void renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                         RayCounters& counters) const override;
  // The radiance arriving along `ray` (as seen by a camera ray: emitters count whole).
  glm::vec3 traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) const override;

 private:
  // settings() for samples [first, first + count) of the pixels.
  RenderSettings passSettings(int first, int count) const;

  std::shared_ptr<const PathLights> lights_;
};

}  // namespace engine::rt
