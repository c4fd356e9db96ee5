#pragma once
// demo --mode raytrace or pathtrace in a window: the scene is traced on the CPU in
// the background, tile by tile, and each frame shows the tiles finished so far (the
// image fills in progressively). The path tracer goes over the image once per
// sample, up to --spp, so the window shows the mean of the samples so far: a noisy
// image at once that clears as it converges. Offscreen, the demo calls
// rt::raytraceScene directly and needs no GL at all.
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "app/game.h"
#include "asset/scene_desc.h"
#include "gl/resources.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"

namespace demo {

class RaytraceGame final : public engine::Game {
 public:
  RaytraceGame(engine::SceneDesc scene, double time, engine::rt::RenderSettings settings);
  ~RaytraceGame() override;

  engine::Status init() override;
  void update(double, double) override {}
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override;

 private:
  void traceTiles();
  struct Progress;
  void tracePass(int pass, Progress& progress);
  void uploadFinishedTiles();

  engine::SceneDesc desc_;
  double time_;
  engine::rt::RenderSettings settings_;
  engine::Camera camera_;
  std::unique_ptr<engine::rt::RtScene> scene_;
  std::unique_ptr<engine::rt::Integrator> integrator_;
  std::vector<std::uint8_t> pixels_;  // RGBA8, top row first, written by the tracer
  std::vector<glm::vec3> sum_;        // linear, the sum of each pixel's samples so far
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
  engine::gl::Framebuffer source_;
};

}  // namespace demo
