#pragma once
// `demo --mode raytrace|pathtrace --device gpu --offscreen`: the scene built as the
// CPU tracer builds it, traced by the GPU Whitted integrator or path tracer
// (engine/gputrace) on an offscreen context, tone mapped by the CPU's own code.
#include <memory>
#include <string>
#include <vector>

#include "app/game.h"
#include "app/runner.h"
#include "asset/scene_desc.h"
#include "core/result.h"
#include "gl/resources.h"
#include "raytrace/scene_builder.h"

namespace engine::gpurt {
class GpuTracer;
class GpuPoses;
}

namespace demo {

// Errors: "--device gpu: double precision is not supported" and the like for what the
// GPU path cannot draw, or a context or shader failure.
engine::Result<engine::rt::RaytraceRun> gpuRaytraceScene(const engine::SceneDesc& scene, double time,
                                                         const engine::rt::RenderSettings& settings,
                                                         engine::Backend backend, const std::string& shaderDir);

// `demo --mode raytrace|pathtrace --device gpu` in a window: the GPU tracer on the
// window's own context, a band of rows of a pass a frame (a pass: the Whitted
// tracer's whole image; the path tracer's next sample of every pixel), the image the
// mean of the passes so far. The bands are sized to about kFrameSeconds of the GPU's
// time, so the window answers while a pass takes seconds (llvmpipe). Each pass is
// the GPU's sum of one sample, summed here in the order the offscreen render's
// kernel sums them, so once every pass is in the image is the offscreen one byte for
// byte. `animate`: the scene moves instead, each pass posed at the time of the frame
// that starts it (its characters' BVHs refitted on the GPU, gpurt::GpuPoses), and a
// pass is the whole still of that pose (the path tracer's every sample), shown
// alone. `wholePasses` (offscreen): a pass a frame, not bands, so that each frame is
// the still of its own time.
class GpuTraceGame final : public engine::Game {
 public:
  GpuTraceGame(engine::SceneDesc scene, double time, engine::rt::RenderSettings settings, std::string shaderDir,
               bool animate = false, bool wholePasses = false);
  ~GpuTraceGame() override;

  engine::Status init() override;
  void update(double, double) override {}
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override;
  // The mean of each pixel's passes so far, as the texture shows it encoded.
  engine::Result<engine::FloatImage> linearFrame() override;

 private:
  engine::Status traceBand(double time);
  // Whether passes add up to one image (the path tracer's samples, still), rather
  // than each standing alone (the Whitted tracer's one pass, an animated pass).
  bool summed() const { return passes_ > 1 && !animate_; }

  engine::SceneDesc desc_;
  double time_;
  engine::rt::RenderSettings settings_;
  std::string shaderDir_;
  engine::Camera camera_;
  bool animate_ = false;
  bool wholePasses_ = false;
  std::unique_ptr<engine::rt::AnimatedRtScene> scene_;
  std::unique_ptr<engine::gpurt::GpuTracer> tracer_;
  std::unique_ptr<engine::gpurt::GpuPoses> poses_;  // with animate_
  std::vector<glm::vec3> sum_;  // linear, each pixel's samples so far
  int done_ = 0, passes_ = 1;
  int row_ = 0;          // the first row of the pass not traced yet
  int bandRows_ = 8;     // rows a frame, sized by the last band's time
  engine::gl::Texture texture_;
  engine::gl::Framebuffer framebuffer_;
};

}  // namespace demo
