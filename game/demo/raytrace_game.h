#pragma once
// demo --mode raytrace or pathtrace in a window: the scene is traced on the CPU in
// the background (progressive_trace.h) and each frame shows what is finished so
// far. Offscreen, the demo calls rt::raytraceScene directly and needs no GL at all.
#include <memory>

#include "app/game.h"
#include "asset/scene_desc.h"
#include "progressive_trace.h"
#include "raytrace/integrator.h"

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
  engine::Result<engine::FloatImage> linearFrame() override { return trace_->linearSnapshot(); }

 private:
  engine::SceneDesc desc_;
  double time_;
  engine::rt::RenderSettings settings_;
  engine::Camera camera_;
  std::unique_ptr<ProgressiveTrace> trace_;
};

}  // namespace demo
