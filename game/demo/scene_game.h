#pragma once
// The demo's game: a scene file drawn by the SceneRenderer, its characters posed at
// the scene time, the camera where the file puts it (and where the window's
// controls move it). In a window it shows the trade panel (trade_panel.h): the
// render knobs changed live, another scene picked, time paused, slowed or scrubbed,
// and what each pass costs on the GPU.
#include <array>
#include <memory>
#include <string>

#include "app/game.h"
#include "asset/scene_desc.h"
#include "render/scene_renderer.h"

namespace engine {
class Scene;
}

namespace demo {

// The panel's time controls: until one is touched, scene time is the runner's.
struct TimeControl {
  bool paused = false;
  double speed = 1.0;
  bool taken = false;  // the user took over: time advances by dt * speed from here
  double time = 0.0;
};

// The panel's graph of the frame's GPU time, newest at `next` - 1.
struct GpuHistory {
  std::array<float, 120> ms{};
  int next = 0;
};

class SceneGame final : public engine::Game {
 public:
  SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options, bool panel = false);
  ~SceneGame() override;

  engine::Status init() override;
  void update(double time, double dt) override;
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override { renderer_.reset(); }
  Counters frameCounters() override;
  bool wantsUi() const override { return panel_; }
  void drawUi() override;

  engine::SceneRenderer* renderer() { return renderer_.get(); }
  const engine::SceneRenderOptions& options() const { return options_; }
  const engine::Scene* scene() const { return scene_.get(); }
  TimeControl& timeControl() { return time_; }

  // Rebuilds the renderer with `options` over the same scene (nothing is
  // reloaded). On failure the current renderer stays and the error is returned.
  engine::Status applyOptions(const engine::SceneRenderOptions& options);
  // Loads another scene file; on failure the current scene stays.
  engine::Status switchScene(const std::string& path);
  // What the panel reports: the last failure to apply or load, or "".
  const std::string& lastError() const { return lastError_; }

 private:
  engine::Status build(std::shared_ptr<engine::Scene> scene, const engine::SceneRenderOptions& options);

  engine::SceneDesc desc_;
  engine::SceneRenderOptions options_;
  bool panel_ = false;
  engine::Camera camera_;
  std::shared_ptr<engine::Scene> scene_;
  std::unique_ptr<engine::SceneRenderer> renderer_;
  engine::Status updated_ = engine::Ok{};
  TimeControl time_;
  std::string lastError_;
  GpuHistory history_;
};

}  // namespace demo
