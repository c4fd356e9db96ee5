#include "raytrace/integrator.h"

#include <utility>

#include "raytrace/path_tracer.h"
#include "raytrace/whitted_tracer.h"

namespace engine::rt {
namespace {

// What a method counts its rays into: the caller's counters, or where it passes none
// a tally that is dropped.
RayCounters& countersOr(RayCounters* counters, RayCounters& dropped) { return counters ? *counters : dropped; }

}  // namespace

Integrator::Integrator(const RtScene& scene, RenderSettings settings) {
  if (settings.method == Method::Path) {
    method_ = std::make_shared<const PathIntegrator>(scene, std::move(settings));
  } else {
    method_ = std::make_shared<const WhittedIntegrator>(scene, std::move(settings));
  }
}

glm::vec3 Integrator::renderPixel(int x, int y, RayCounters* counters) const {
  RayCounters dropped;
  return method_->renderPixel(x, y, countersOr(counters, dropped));
}

glm::vec3 Integrator::renderPixelSamples(int x, int y, int first, int count, RayCounters* counters) const {
  RayCounters dropped;
  return method_->renderPixelSamples(x, y, first, count, countersOr(counters, dropped));
}

void Integrator::renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                                   RayCounters* counters) const {
  RayCounters dropped;
  method_->renderSpanSamples(x0, x1, y, first, count, out, countersOr(counters, dropped));
}

glm::vec3 Integrator::traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters* counters) const {
  RayCounters dropped;
  return method_->traceRay(ray, seed, countersOr(counters, dropped));
}

}  // namespace engine::rt
