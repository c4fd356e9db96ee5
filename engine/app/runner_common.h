#pragma once
// Pieces both runners share: context set-up and the end-of-run outputs.
#include <memory>
#include <utility>
#include <vector>

#include "app/runner.h"
#include "render/render_target.h"

namespace engine {

// Shuts the game down when the run ends, however it ends (an init that failed
// half-way, a frame's error, an unwritable output): declared after the context in
// RunSetup, it is destroyed before it, so every GL object the game made is deleted
// while its context still exists.
class GameSession {
 public:
  explicit GameSession(Game& game) : game_(&game) {}
  GameSession(GameSession&& other) noexcept : game_(std::exchange(other.game_, nullptr)) {}
  GameSession& operator=(GameSession&&) = delete;
  ~GameSession() {
    if (game_) game_->shutdown();
  }

 private:
  Game* game_;
};

// Members are destroyed bottom-up: the target, then the game's objects, then the
// context they belong to.
struct RunSetup {
  std::unique_ptr<GlContext> context;
  GameSession session;
  RenderTarget target;
};

// Creates the context, turns on debug output when asked, initialises the game and
// makes the render target. The game is shut down when the RunSetup goes, or
// before this returns an error.
Result<RunSetup> startRun(Backend backend, Game& game, const RunOptions& options);

// The screenshot in the format its name asks for: `frame` as PNG, or the game's
// linear frame (Game::linearFrame, of the frame's size) as OpenEXR or PFM.
Status writeScreenshot(const std::string& path, Game& game, const Image& frame);

// Writes the bench JSON (with the game's counters of the last frame) and the
// screenshot, as the options ask. Call it while the RunSetup lives.
Status finishRun(const GlContext& context, const RunOptions& options, Game& game,
                 std::vector<double> frameMs, const Image* lastFrame);

}  // namespace engine
