#include "scene_game.h"

namespace demo {

SceneGame::SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options)
    : scene_(std::move(scene)), options_(std::move(options)) {}

SceneGame::~SceneGame() = default;

engine::Status SceneGame::init() {
  auto renderer = engine::SceneRenderer::create(scene_, options_);
  if (!renderer) return renderer.error();
  renderer_ = std::move(renderer).value();
  camera_ = renderer_->initialCamera();
  return engine::Ok{};
}

// A failed pose ends the run at the next render, which has no frame to show.
void SceneGame::update(double time, double) { updated_ = renderer_->update(time); }

engine::Status SceneGame::render(const engine::FrameInfo& frame) {
  if (!updated_) return updated_;
  return renderer_->render(camera_, frame.width, frame.height);
}

engine::Game::Counters SceneGame::frameCounters() {
  const engine::SceneStats& s = renderer_->stats();
  return {{"draw_calls", s.drawCalls},
          {"program_changes", s.programChanges},
          {"objects_drawn", s.objectsDrawn},
          {"objects_culled", s.objectsCulled},
          {"terrain_triangles", s.terrainTriangles},
          {"triangles_all_passes", double(renderer_->lastFrameTriangles())}};
}

}  // namespace demo
