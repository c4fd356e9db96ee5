#pragma once
// The demo's soak run (demo --soak SECONDS): the scene drawn as the demo draws it
// while the camera circles what it looks at and the scene is reloaded from its file
// every few seconds (counted from the end of the last rebuild, after at least one
// frame of it). Before each reload it samples the process's resident memory
// and the live GL objects; a renderer that leaks shows as a rise from one sample to
// the next, as every reload builds the same scene again.
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "app/game.h"
#include "scene_game.h"

namespace demo {

struct SoakSample {
  double seconds = 0.0;  // wall time since the first frame
  long long frames = 0;
  double rssMiB = 0.0;
  long long glObjects = 0;
};

// Resident set size of this process, from /proc/self/statm; 0 where unreadable.
double residentMiB();

class SoakGame final : public engine::Game {
 public:
  SoakGame(std::string scenePath, engine::SceneRenderOptions options, double seconds, double reloadEvery);

  engine::Status init() override;
  void update(double time, double dt) override;
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return scene_->camera(); }
  void shutdown() override { scene_.reset(); }
  bool finished() const override { return finished_; }
  engine::Result<engine::FloatImage> linearFrame() override { return scene_->linearFrame(); }

  const std::vector<SoakSample>& samples() const { return samples_; }
  // One line per sample and a summary: first and last RSS and GL object counts.
  std::string report() const;

 private:
  engine::Status reload();
  void orbit(double seconds);

  std::string scenePath_;
  engine::SceneRenderOptions options_;
  double seconds_, reloadEvery_;
  std::unique_ptr<SceneGame> scene_;
  engine::Status error_ = engine::Ok{};  // a failed reload, reported by the next frame
  glm::dvec3 target_{0.0}, offset_{0.0};  // the orbit: the camera circles target_
  std::chrono::steady_clock::time_point start_;
  bool started_ = false, finished_ = false;
  double nextReload_ = 0.0;
  long long frames_ = 0, framesSinceReload_ = 0;
  std::vector<SoakSample> samples_;
};

}  // namespace demo
