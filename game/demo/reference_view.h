#pragma once
// The trade panel's reference view (issue 17): the tracer renders the window's
// current view of the same scene (the scene layer's poses at its current time)
// progressively on worker threads while the rasterizer keeps drawing, and restarts
// when the view, the time, the size or the method changes. Against it the panel
// shows the raster frame's error at the reference's current spp: PSNR, mean error,
// SSIM and a heatmap.
#include <memory>
#include <optional>

#include "core/image.h"
#include "core/result.h"
#include "gl/resources.h"
#include "progressive_trace.h"
#include "raytrace/integrator.h"

namespace engine {
class Scene;
}

namespace demo {

struct ReferenceRequest {
  engine::CameraDesc camera;
  double time = 0.0;
  int width = 0, height = 0;
  engine::rt::RenderSettings settings;  // method, spp, depth, seed (width and height are the request's)
  // The terrain the window draws: its LOD's image height (0: the request's height)
  // and the renderer's override of the LOD target (0: the file's).
  int terrainViewportHeight = 0;
  double terrainErrorOverride = 0.0;
  bool sameAs(const ReferenceRequest& o) const;
};

struct ReferenceError {
  int spp = 0;  // the reference's samples so far
  double psnr = 0.0, meanAbs = 0.0, ssim = 0.0;
  // The reference's own noise (ProgressiveTrace::noisePsnr): a raster PSNR near it
  // or above it says more about the reference than the raster.
  std::optional<double> noisePsnr;
};

class ReferenceView {
 public:
  // Starts tracing `request` unless it is the one being traced. Needs a context.
  engine::Status update(std::shared_ptr<engine::Scene> scene, const ReferenceRequest& request);
  void stop() { trace_.reset(); }
  // Stops and drops the GL objects (before the context goes).
  void release() {
    trace_.reset();
    heatmap_.reset();
  }
  bool running() const { return trace_ != nullptr; }
  ProgressiveTrace* trace() { return trace_.get(); }
  const ReferenceRequest& request() const { return request_; }

  // The error of `raster` (the same view at the reference's size, top row first)
  // against the reference so far; the heatmap texture shows it (diffImage, x4).
  engine::Result<ReferenceError> compare(const engine::Image& raster);
  const engine::gl::Texture& heatmap() const { return heatmap_; }

 private:
  std::unique_ptr<ProgressiveTrace> trace_;
  ReferenceRequest request_;
  engine::gl::Texture heatmap_;
};

}  // namespace demo
