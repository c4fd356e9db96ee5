#pragma once
// Pieces both runners share: context set-up and the end-of-run outputs.
#include <memory>
#include <vector>

#include "app/runner.h"
#include "render/render_target.h"

namespace engine {

struct RunSetup {
  std::unique_ptr<GlContext> context;
  RenderTarget target;
};

// Creates the context, turns on debug output when asked, initialises the game and
// makes the render target.
Result<RunSetup> startRun(Backend backend, Game& game, const RunOptions& options);

// Writes the bench JSON (with the game's counters of the last frame) and the
// screenshot, as the options ask. Call it before the game shuts down.
Status finishRun(const GlContext& context, const RunOptions& options, Game& game,
                 std::vector<double> frameMs, const Image* lastFrame);

}  // namespace engine
