#pragma once
// The two loops: interactive (a GLFW window) and headless (N frames at a fixed step
// into an offscreen framebuffer, read back to a PNG). Both call the same Game and
// draw into the same kind of RenderTarget, so the frame at time T is the same image
// whichever way it was made.
#include <functional>
#include <optional>
#include <string>

#include "app/game.h"
#include "core/image.h"
#include "platform/gl_context.h"

namespace engine {

struct RunOptions {
  int width = 1280;
  int height = 720;
  double dt = 1.0 / 60.0;
  // Scene time of the last (captured) frame; default (frames-1)*dt. In a real-time
  // window: the time the clock starts at.
  std::optional<double> time;
  // Frames rendered, the last one at `time`, each at a fixed step (a window then
  // shows exactly what headless renders). Window only: 0 = real time until closed.
  int frames = 1;
  int msaa = 1;             // as asked (and reported by --bench)
  int targetSamples = 0;    // samples of the runner's own target; 0: msaa (a game
                            // that multisamples itself asks for 1)
  std::string screenshot;  // PNG of the last frame; empty = none
  // Window runs of a fixed number of frames: the screenshot is the whole window as
  // shown, ImGui panels included, not only the game's frame.
  bool screenshotWindow = false;
  std::string benchFile;   // frame-time JSON; empty = none
  std::string command;     // the command line, recorded in the bench report
  bool vsync = true;
#ifdef NDEBUG
  bool debugGl = false;
#else
  bool debugGl = true;  // debug builds report every GL error
#endif
};

// Scene time of headless frame `index` out of `options.frames`.
double headlessFrameTime(const RunOptions& options, int index);

// Renders headlessly through `backend` (Egl or OsMesa). When `captured` is not null
// the last frame is also returned there; `afterFrames` runs while the context is
// still alive (to report on what the game built).
Status runHeadless(Backend backend, Game& game, const RunOptions& options,
                   Image* captured = nullptr, const std::function<void()>& afterFrames = {});

// Opens a window and runs until it is closed (or `frames` frames were shown).
Status runWindow(Game& game, const RunOptions& options);

// glibc returns freed memory above the trim threshold to the kernel; llvmpipe frees
// and re-allocates its per-frame buffers, so with the default every page faults back
// in each frame (3x slower frames measured at 50 characters). Called by the runners.
void keepFreedMemory();

}  // namespace engine
