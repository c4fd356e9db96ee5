#pragma once
// The CPU tracer's scene traced on the GPU in GL 4.5 compute shaders (shaders/rt/):
// the scene flattened by gputrace/gpu_layout.h into shader storage buffers, ray
// queries (closest and any hit, what the tests compare with the CPU's), the
// Whitted integrator of raytrace/whitted_tracer.h and the path tracer of
// raytrace/path_tracer.h. Above both raytrace/ (which never
// touches GL) and gl/; needs a current GL 4.5 context.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "gputrace/gpu_refit.h"
#include "raytrace/render_types.h"
#include "raytrace/rt_scene.h"

namespace engine::gpurt {

// A ray for trace(): origin and tMax, direction.
struct RayQuery {
  glm::vec4 originTMax;
  glm::vec4 direction;
};

enum class HitKind : std::int32_t { None = 0, Sphere = 1, Plane = 2, Triangle = 3 };

struct RayAnswer {
  float t;        // the closest hit's, or tMax
  HitKind kind;
  std::uint32_t index;   // the sphere, the plane, or the triangle's global id (GpuSceneLayout)
  std::uint32_t anyHit;  // 1 when the any-hit query found something
};
static_assert(sizeof(RayAnswer) == 16);

// Why the GPU tracer (Whitted or path, by settings.method) cannot draw this scene
// with these settings yet, as the one line a command line prints after "--device
// gpu: "; empty when it can.
std::string unsupported(const rt::RtScene& scene, const rt::RenderSettings& settings);

// What the GPU tracer builds for the scene (demo --describe --device gpu): its kernel
// with the variant's defines (what the scene needs built in), the BVH layout and the
// storage buffers it uploads, with their sizes. Needs no GL context.
std::string describe(const rt::RtScene& scene, const rt::RenderSettings& settings);

class GpuTracer {
 public:
  // Flattens and uploads the scene (it must stay unchanged while this lives) and
  // builds the programs; errors are shader compile errors. `width`: the BVH layout,
  // 8 or 4 wide (gputrace/gpu_layout.h); 4 traced twice as fast on llvmpipe.
  static Result<GpuTracer> create(const rt::RtScene& scene, const std::string& shaderDir, int width = 4);

  // Each ray's closest hit and any hit.
  std::vector<RayAnswer> trace(std::span<const RayQuery> rays) const;
  // The image Integrator(scene, settings).render() makes, Whitted or path traced
  // (check unsupported() first). `seconds` is the GPU's time, the upload excluded.
  Result<rt::RenderResult> render(const rt::RenderSettings& settings) const;
  // Rows [firstRow, firstRow + rows) of that image, each pixel the same bits as in the
  // whole image (a window traces a pass a band at a time, a GPU's watchdog never
  // sees a long dispatch): the result's image is those rows, `rows` high.
  Result<rt::RenderResult> render(const rt::RenderSettings& settings, int firstRow, int rows) const;

  // The flattened scene it traces, and the buffers it lives in: a GpuRefit made from
  // this layout refits a group of it in place.
  const rt::GpuSceneLayout& layout() const;
  GpuRefit::Targets buffers() const;

  GpuTracer(GpuTracer&&) noexcept;
  GpuTracer& operator=(GpuTracer&&) noexcept;
  ~GpuTracer();

 private:
  GpuTracer();
  Result<rt::RenderResult> renderWhitted(const rt::RenderSettings& settings, int firstRow, int rows) const;
  // path_kernel.cpp.
  Result<rt::RenderResult> renderPath(const rt::RenderSettings& settings, int firstRow, int rows) const;
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace engine::gpurt
