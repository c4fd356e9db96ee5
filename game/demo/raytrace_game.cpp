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
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  // The texture holds encoded display values: copy them as they are, flipped (the
  // image's first row is the top one).
  glDisable(GL_FRAMEBUFFER_SRGB);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBlitNamedFramebuffer(trace_->framebuffer().id(), GLuint(target), 0, 0, trace_->width(), trace_->height(), 0,
                         frame.height, frame.width, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return engine::Ok{};
}

void RaytraceGame::shutdown() { trace_.reset(); }

}  // namespace demo
