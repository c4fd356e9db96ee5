#pragma once
// A traced image that fills in while the window keeps drawing: the scene is traced
// on a worker thread, tile by tile (TBB), and each frame uploads the tiles
// finished since the last. The path tracer goes over the image once per sample, up
// to the settings' spp, so the image is the mean of the samples so far: noisy at
// once, clearing as it converges, and in the end exactly the offscreen image
// (renderSpanSamples gives each pixel the same RNG streams as render(), and traces a
// tile's rows as render() does: the Whitted packets, the path tracer's batches). Used by
// demo --mode raytrace|pathtrace in a window and by the trade panel's reference.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/image.h"
#include "core/linear_image.h"
#include "core/result.h"
#include "gl/resources.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"

namespace engine {
struct FrameInfo;
}

namespace demo {

// Fills the bound draw framebuffer with a traced image of `width` x `height` (encoded
// display values, its first row the image's top), as it is, stretched to the frame:
// the tracers' windows, CPU and GPU.
void showTracedImage(const engine::gl::Framebuffer& image, int width, int height, const engine::FrameInfo& frame);

class ProgressiveTrace {
 public:
  // Starts tracing at once; `progressBar` prints one on stderr. Needs a current
  // context (the image's texture).
  static engine::Result<std::unique_ptr<ProgressiveTrace>> start(std::unique_ptr<engine::rt::RtScene> scene,
                                                                 const engine::rt::RenderSettings& settings,
                                                                 bool progressBar);
  // Cancels the trace and waits for its worker.
  ~ProgressiveTrace();

  // Copies the tiles finished since the last call into the texture.
  void uploadFinishedTiles();
  // The image so far (encoded display values, top row first in memory; row 0 of the
  // framebuffer is the image's top row).
  const engine::gl::Framebuffer& framebuffer() const { return framebuffer_; }
  const engine::gl::Texture& texture() const { return texture_; }
  int width() const { return settings_.width; }
  int height() const { return settings_.height; }
  // Passes every tile has finished, and how many there will be.
  int passesDone() const;
  int passes() const { return passes_; }
  // The image's own noise as a PSNR (dB) against the image it converges to,
  // estimated from two halves of its samples: the even passes' mean against the odd
  // passes' (in displayed values). Empty before every tile has two passes (the
  // Whitted tracer has one).
  std::optional<double> noisePsnr() const;
  // A copy of the encoded image as it stands.
  engine::Image snapshot() const;
  // The linear image as it stands: each pixel the mean of its samples so far, before
  // exposure, tone map and curve (the path tracer's offscreen framebuffer once done).
  engine::FloatImage linearSnapshot() const;

 private:
  ProgressiveTrace() = default;
  struct Progress;
  struct TileSpan {
    int x0, x1, y0, y1;
    int passes;  // finished
  };
  // Calls `visit` with every tile, under the tile's lock.
  void forEachTile(const std::function<void(const TileSpan&)>& visit) const;
  void traceTiles();
  void tracePass(int pass, Progress& progress);

  std::unique_ptr<engine::rt::RtScene> scene_;
  engine::rt::RenderSettings settings_;
  std::unique_ptr<engine::rt::Integrator> integrator_;
  bool progressBar_ = false;
  std::vector<std::uint8_t> pixels_;  // RGBA8, top row first, written by the tracer
  std::vector<glm::vec3> sum_;        // linear, the sum of each pixel's samples so far
  std::vector<glm::vec3> oddSum_;     // the same over the odd passes only (noisePsnr)
  std::unique_ptr<std::atomic<int>[]> tilePasses_;  // passes each tile has finished
  std::vector<int> tileUploaded_;                   // the passes each tile showed
  // A tile's bytes are rewritten each pass: the tracer encodes and the window uploads
  // them under the tile's lock, never at once.
  std::unique_ptr<std::mutex[]> tileLocks_;
  int passes_ = 1;
  int tilesX_ = 0, tilesY_ = 0;
  std::atomic<bool> cancel_{false};
  std::thread worker_;
  engine::gl::Texture texture_;
  engine::gl::Framebuffer framebuffer_;
};

}  // namespace demo
