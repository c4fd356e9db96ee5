#pragma once
// The CPU ray tracer's entry point: an RtScene rendered with RenderSettings
// (render_types.h) by the method they name, the course's Whitted tracer
// (whitted_tracer.h: direct light with shadow rays, mirrors, ambient) or the
// physically based path tracer (path_tracer.h), both behind IntegratorMethod
// (integrator_method.h). The output is a linear float RGB framebuffer; tone_map.h
// turns it into an 8-bit image.
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "raytrace/integrator_method.h"
#include "raytrace/ray.h"
#include "raytrace/render_types.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

class Integrator {
 public:
  // The scene must outlive the integrator and stay unchanged while it renders.
  Integrator(const RtScene& scene, RenderSettings settings);

  // Renders every pixel over 16 x 16 tiles in parallel (TBB).
  RenderResult render() const { return method_->render(); }
  // One pixel's linear colour, exactly as render() computes it (same RNG stream).
  glm::vec3 renderPixel(int x, int y, RayCounters* counters = nullptr) const;
  // The path tracer's mean of samples [first, first + count) of a pixel (a pass of a
  // progressive render); the Whitted tracer's renderPixel, whatever first and count.
  glm::vec3 renderPixelSamples(int x, int y, int first, int count, RayCounters* counters = nullptr) const;
  // renderPixelSamples of pixels x0 .. x1 - 1 of row y into out[0 ..], traced as
  // render() traces a tile's row (the Whitted tracer's packets, the path tracer's
  // paths side by side): the same colours, faster than pixel by pixel. What the
  // window's progressive trace calls.
  void renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                         RayCounters* counters = nullptr) const;
  // The radiance along one ray (as a reflected ray at depth 0 would see it), in the
  // chosen precision; the RNG for area-light samples is seeded from `seed`.
  glm::vec3 traceRay(const Ray<double>& ray, std::uint64_t seed = 0, RayCounters* counters = nullptr) const;

  const RenderSettings& settings() const { return method_->settings(); }

 private:
  std::shared_ptr<const IntegratorMethod> method_;  // the Whitted or the path tracer
};

}  // namespace engine::rt
