#pragma once
// demo --mode raytrace in a window: the scene is traced on the CPU in the
// background, tile by tile, and each frame shows the tiles finished so far (the
// image fills in progressively). Offscreen, the demo calls rt::raytraceScene
// directly and needs no GL at all.
#include <atomic>
#include <memory>
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
  void uploadFinishedTiles();

  engine::SceneDesc desc_;
  double time_;
  engine::rt::RenderSettings settings_;
  engine::Camera camera_;
  std::unique_ptr<engine::rt::RtScene> scene_;
  std::unique_ptr<engine::rt::Integrator> integrator_;
  std::vector<std::uint8_t> pixels_;  // RGBA8, top row first, written by the tracer
  std::unique_ptr<std::atomic<bool>[]> tileDone_;
  std::vector<bool> tileUploaded_;
  int tilesX_ = 0, tilesY_ = 0;
  std::atomic<bool> cancel_{false};
  std::thread worker_;
  engine::gl::Texture texture_;
  engine::gl::Framebuffer source_;
};

}  // namespace demo
