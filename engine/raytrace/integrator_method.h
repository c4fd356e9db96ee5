#pragma once
// What an Integrator (integrator.h) asks of the method that RenderSettings::method
// names: the course's Whitted tracer (whitted_tracer.h) or the path tracer
// (path_tracer.h). A virtual call a render, a span of a row, a pixel or a ray; each
// method traces them with its own templates inside, with no virtual call per ray or
// sample.
#include <cstdint>
#include <utility>

#include <glm/glm.hpp>

#include "raytrace/ray.h"
#include "raytrace/render_types.h"

namespace engine::rt {

class RtScene;

class IntegratorMethod {
 public:
  // The scene must outlive the method and stay unchanged while it renders.
  IntegratorMethod(const RtScene& scene, RenderSettings settings) : scene_(&scene), settings_(std::move(settings)) {}
  IntegratorMethod(const IntegratorMethod&) = delete;
  IntegratorMethod& operator=(const IntegratorMethod&) = delete;
  virtual ~IntegratorMethod() = default;

  const RenderSettings& settings() const { return settings_; }

  // Every pixel over tiles in parallel (TBB; tile_render.h).
  virtual RenderResult render() const = 0;
  // One pixel's linear colour, exactly as render() computes it (same RNG stream).
  virtual glm::vec3 renderPixel(int x, int y, RayCounters& counters) const = 0;
  // The mean of samples [first, first + count) of a pixel (a pass of a progressive
  // render), where the method's samples come in passes; else renderPixel.
  virtual glm::vec3 renderPixelSamples(int x, int y, int first, int count, RayCounters& counters) const = 0;
  // renderPixelSamples of pixels x0 .. x1 - 1 of row y into out[0 ..], traced as
  // render() traces a tile's row: the same colours, faster than pixel by pixel.
  virtual void renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                                 RayCounters& counters) const = 0;
  // The radiance along one ray (as a reflected ray at depth 0 would see it), in the
  // settings' precision; the RNG for light samples is seeded from `seed`.
  virtual glm::vec3 traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) const = 0;

 protected:
  const RtScene& scene() const { return *scene_; }

 private:
  const RtScene* scene_;
  RenderSettings settings_;
};

}  // namespace engine::rt
