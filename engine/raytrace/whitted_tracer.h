#pragma once
// The Whitted-style integrator of the course: primary rays through stratified pixel
// samples, direct light from point, sun and rectangular area lights with shadow rays,
// perfect mirror reflection to a maximum depth, sky or background for rays that escape.
// Shading::Classic is the course's model; Shading::Pbr a Lambert + GGX one. Where the
// scene allows, a row's camera samples are traced eight at a time (whitted_packets.h),
// else their first hits found eight at a time (firstHitsInRows), else one by one: the
// same colours bit for bit. Reached through Integrator (integrator.h).
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "raytrace/integrator_method.h"
#include "raytrace/ray.h"
#include "raytrace/render_types.h"

namespace engine::rt {

class RtScene;
class WhittedPackets;

class WhittedIntegrator final : public IntegratorMethod {
 public:
  WhittedIntegrator(const RtScene& scene, RenderSettings settings);

  RenderResult render() const override;
  glm::vec3 renderPixel(int x, int y, RayCounters& counters) const override;
  // renderPixel: the Whitted tracer's samples come all at once, whatever first and count.
  glm::vec3 renderPixelSamples(int x, int y, int first, int count, RayCounters& counters) const override;
  void renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                         RayCounters& counters) const override;
  glm::vec3 traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) const override;

  // Whether the tracer, where its packets do not apply, finds each row's camera rays'
  // first hits eight at a time (whitted_tracer.cpp's SpanTracer): float precision on a
  // CPU with AVX2. render(), renderSpanSamples() and describe() ask it.
  static bool firstHitsInRows(const RenderSettings& settings);

 private:
  // The packets, where they apply (whitted_packets.h).
  std::shared_ptr<const WhittedPackets> packets_;
};

}  // namespace engine::rt
