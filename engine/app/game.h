#pragma once
// What a program plugs into the runners (sokol's shape: initialise, then per frame
// update and draw, then shut down by destruction).
#include <string>
#include <utility>
#include <vector>

#include "core/linear_image.h"
#include "core/result.h"
#include "render/camera.h"

namespace engine {

class RenderTarget;

struct FrameInfo {
  double time = 0.0;  // scene time of this frame, seconds
  int width = 0;
  int height = 0;
};

class Game {
 public:
  virtual ~Game() = default;
  // Called once with a current GL context, before any frame.
  virtual Status init() = 0;
  // Advances the simulation to `time` by one fixed step `dt`.
  virtual void update(double time, double dt) = 0;
  // Draws the frame into the bound render target. An error ends the run: the
  // runner reports it and exits, never showing or writing a frame it lacks.
  virtual Status render(const FrameInfo& frame) = 0;
  // True once the game has done what it runs for (a soak of fixed length): the
  // runners then stop as if the window were closed or the frames were done.
  virtual bool finished() const { return false; }
  // The camera the interactive controls move.
  virtual Camera& camera() = 0;
  // Releases GL objects while the context is still current; the runners call it
  // before the context goes away.
  virtual void shutdown() = 0;
  // A Dear ImGui panel, drawn over the frame in a window only (never in the
  // captured image). Games without one leave wantsUi() false.
  virtual bool wantsUi() const { return false; }
  virtual void drawUi() {}
  // What the last frame cost in work, not time (draw calls, program changes,
  // triangles...), for `--bench`. Read with the context current, after the frame.
  using Counters = std::vector<std::pair<std::string, double>>;
  virtual Counters frameCounters() { return {}; }
  // The last frame's linear radiance, before exposure, tone map and output curve,
  // top row first: what --screenshot F.exr or F.pfm writes. Read with the context
  // current, after the frame. A game without one says why.
  virtual Result<FloatImage> linearFrame() { return makeError("this program has no linear image of its frames"); }
};

}  // namespace engine
