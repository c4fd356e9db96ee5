#include "scene_game.h"

#include "asset/scene_file.h"
#include "scene/scene.h"

namespace demo {

SceneGame::SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options, bool panel)
    : desc_(std::move(scene)), options_(std::move(options)), panel_(panel) {}

SceneGame::~SceneGame() = default;

engine::Status SceneGame::build(std::shared_ptr<engine::Scene> scene, const engine::SceneRenderOptions& options) {
  auto renderer = engine::SceneRenderer::create(scene, options);
  if (!renderer) return renderer.error();
  renderer_ = std::move(renderer).value();
  scene_ = std::move(scene);
  options_ = options;
  return engine::Ok{};
}

engine::Status SceneGame::init() {
  auto scene = engine::Scene::load(desc_);
  if (!scene) return scene.error();
  if (auto s = build(std::move(scene).value(), options_); !s) return s;
  camera_ = renderer_->initialCamera();
  return engine::Ok{};
}

engine::Status SceneGame::applyOptions(const engine::SceneRenderOptions& options) {
  const engine::Status status = build(scene_, options);
  lastError_ = status ? "" : status.error().message;
  if (status) updated_ = renderer_->update(scene_->time());
  return status;
}

engine::Status SceneGame::switchScene(const std::string& path) {
  auto desc = engine::loadSceneFile(path);
  engine::Status status = engine::Ok{};
  if (!desc) {
    status = desc.error();
  } else if (auto scene = engine::Scene::load(*desc); !scene) {
    status = scene.error();
  } else if (status = build(std::move(scene).value(), options_); status) {
    desc_ = std::move(desc).value();
    camera_ = renderer_->initialCamera();
    updated_ = renderer_->update(time_.taken ? time_.time : 0.0);
  }
  lastError_ = status ? "" : status.error().message;
  return status;
}

// A failed pose ends the run at the next render, which has no frame to show.
void SceneGame::update(double time, double dt) {
  if (!time_.taken) {
    time_.time = time;
  } else if (!time_.paused) {
    time_.time += dt * time_.speed;
  }
  updated_ = renderer_->update(time_.time);
}

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
