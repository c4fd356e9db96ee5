#include "soak_game.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/gtc/constants.hpp>

#include "asset/scene_file.h"
#include "gl/object.h"

namespace demo {
namespace {
constexpr double kOrbitSeconds = 20.0;  // one turn around the target
constexpr double kOrbitDistance = 10.0;  // metres ahead of the scene's camera
}  // namespace

double residentMiB() {
  std::ifstream statm("/proc/self/statm");
  long long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0.0;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

SoakGame::SoakGame(std::string scenePath, engine::SceneRenderOptions options, double seconds, double reloadEvery)
    : scenePath_(std::move(scenePath)), options_(std::move(options)), seconds_(seconds), reloadEvery_(reloadEvery) {}

engine::Status SoakGame::init() {
  if (auto s = reload(); !s) return s;
  const engine::Camera& c = scene_->camera();
  target_ = c.position + c.forward() * kOrbitDistance;
  offset_ = c.position - target_;
  return engine::Ok{};
}

// The same file, loaded and built again from nothing, in place of the old scene
// (which is shut down first: its objects go before the new ones exist).
engine::Status SoakGame::reload() {
  auto desc = engine::loadSceneFile(scenePath_);
  if (!desc) return desc.error();
  if (scene_) scene_->shutdown();
  scene_ = std::make_unique<SceneGame>(std::move(desc).value(), options_);
  return scene_->init();
}

void SoakGame::orbit(double seconds) {
  const double angle = glm::two_pi<double>() * seconds / kOrbitSeconds;
  const double c = std::cos(angle), s = std::sin(angle);
  engine::Camera& camera = scene_->camera();
  camera.position = target_ + glm::dvec3(c * offset_.x + s * offset_.z, offset_.y, -s * offset_.x + c * offset_.z);
  camera.lookAt(target_);
}

void SoakGame::update(double time, double dt) {
  if (finished_) return;  // a window's frame may hold several steps
  const auto now = std::chrono::steady_clock::now();
  if (!started_) {
    start_ = now;
    started_ = true;
    nextReload_ = reloadEvery_;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // Sampled only after a frame of the current build: some objects are made by its
  // first frame (queries, pages), and a slow build (under ASan it outlasts the
  // interval) would otherwise be sampled, and rebuilt, before it drew anything.
  const bool drawn = framesSinceReload_ > 0;
  if (drawn && (elapsed >= nextReload_ || elapsed >= seconds_)) {
    samples_.push_back({elapsed, frames_, residentMiB(), engine::gl::liveObjects()});
    const SoakSample& s = samples_.back();
    std::fprintf(stderr, "soak: %7.1f s, %8lld frames, RSS %8.1f MiB, %6lld GL objects\n", s.seconds, s.frames,
                 s.rssMiB, s.glObjects);
    if (elapsed >= seconds_) {
      finished_ = true;
      return;
    }
    if (auto status = reload(); !status) error_ = status;
    framesSinceReload_ = 0;
    nextReload_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() + reloadEvery_;
  }
  if (!error_) return;
  scene_->update(time, dt);
}

engine::Status SoakGame::render(const engine::FrameInfo& frame) {
  if (!error_) return error_;
  // The camera moves every frame, not every step: a frame with no step (frames
  // faster than the fixed step) would stand still, and a still camera makes
  // objects of its own (the kept sun map), in some builds and not in others as the
  // machine's load decides, and the count of GL objects compared across builds
  // would differ with no leak.
  if (started_) orbit(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  ++frames_;
  ++framesSinceReload_;
  return scene_->render(frame);
}

std::string SoakGame::report() const {
  if (samples_.size() < 2) return "soak: too short for two samples\n";
  // The first sample is taken after the first build has warmed up (shaders, driver
  // pools); the change from it to the last is what the reloads cost.
  const SoakSample& a = samples_.front();
  const SoakSample& b = samples_.back();
  char line[256];
  std::snprintf(line, sizeof line,
                "soak summary: %.0f s, %lld frames, %zu reloads; RSS %.1f -> %.1f MiB (%+.1f), GL objects %lld -> %lld\n",
                b.seconds, b.frames, samples_.size() - 1, a.rssMiB, b.rssMiB, b.rssMiB - a.rssMiB, a.glObjects,
                b.glObjects);
  return line;
}

}  // namespace demo
