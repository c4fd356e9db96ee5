#include <algorithm>
#include <chrono>

#include "app/frame_stats.h"
#include "app/runner_common.h"

namespace engine {

double headlessFrameTime(const RunOptions& options, int index) {
  const double last = options.time ? *options.time : double(options.frames - 1) * options.dt;
  // Computed from the index, not accumulated, so the captured frame's time is
  // exactly `last` however many frames ran before it.
  return last - double(options.frames - 1 - index) * options.dt;
}

Status runHeadless(Backend backend, Game& game, const RunOptions& options, Image* captured,
                   const std::function<void()>& afterFrames) {
  auto setup = startRun(backend, game, options);
  if (!setup) return setup.error();
  const RenderTarget& target = setup->target;

  std::vector<double> frameMs;
  // A soak asks for every frame there is (INT_MAX) and stops when the game is done.
  frameMs.reserve(static_cast<size_t>(std::min(options.frames, 1 << 16)));
  for (int i = 0; i < options.frames && !game.finished(); ++i) {
    const double time = headlessFrameTime(options, i);
    const auto start = std::chrono::steady_clock::now();
    game.update(time, options.dt);
    target.bind();
    if (auto s = game.render({time, target.width(), target.height()}); !s) return s;
    target.resolve();
    // The frame is finished when the GL is: count the rasterizer's work too.
    glFinish();
    noteFrameFinished();
    const auto end = std::chrono::steady_clock::now();
    frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
  }
  Image last = target.readPixels();
  if (afterFrames) afterFrames();
  auto status = finishRun(*setup->context, options, game, std::move(frameMs), &last);
  if (captured) *captured = std::move(last);
  return status;
}

}  // namespace engine
