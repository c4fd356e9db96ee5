#pragma once
// The demo's game: a scene file drawn by the SceneRenderer, its characters posed at
// the scene time, the camera where the file puts it (and where the window's
// controls move it).
#include <memory>

#include "app/game.h"
#include "asset/scene_desc.h"
#include "render/scene_renderer.h"

namespace demo {

class SceneGame final : public engine::Game {
 public:
  SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options);
  ~SceneGame() override;

  engine::Status init() override;
  void update(double time, double dt) override;
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override { renderer_.reset(); }
  Counters frameCounters() override;

  engine::SceneRenderer* renderer() { return renderer_.get(); }

 private:
  engine::SceneDesc scene_;
  engine::SceneRenderOptions options_;
  engine::Camera camera_;
  std::unique_ptr<engine::SceneRenderer> renderer_;
  engine::Status updated_ = engine::Ok{};
};

}  // namespace demo
