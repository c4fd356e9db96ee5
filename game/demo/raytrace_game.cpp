#include "raytrace_game.h"

#include "raytrace/scene_builder.h"

namespace demo {

RaytraceGame::RaytraceGame(engine::SceneDesc scene, double time, engine::rt::RenderSettings settings)
    : desc_(std::move(scene)), time_(time), settings_(std::move(settings)) {}

RaytraceGame::~RaytraceGame() { shutdown(); }

engine::Status RaytraceGame::init() {
  auto scene = engine::rt::buildRtScene(desc_, time_, settings_.height);
  if (!scene) return scene.error();
  auto trace = ProgressiveTrace::start(std::make_unique<engine::rt::RtScene>(std::move(scene).value()), settings_, true);
  if (!trace) return trace.error();
  trace_ = std::move(trace).value();
  return engine::Ok{};
}

engine::Status RaytraceGame::render(const engine::FrameInfo& frame) {
  trace_->uploadFinishedTiles();
  showTracedImage(trace_->framebuffer(), trace_->width(), trace_->height(), frame);
  return engine::Ok{};
}

void RaytraceGame::shutdown() { trace_.reset(); }

}  // namespace demo
