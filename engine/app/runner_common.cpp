#include "app/runner_common.h"

#include <malloc.h>

#include "app/frame_stats.h"
#include "core/float_image_io.h"
#include "gl/debug.h"

namespace engine {

void keepFreedMemory() {
  // 1 GiB: far above any per-frame allocation, far below the machine's memory.
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

Result<RunSetup> startRun(Backend backend, Game& game, const RunOptions& options) {
  keepFreedMemory();
  ContextOptions contextOptions;
  contextOptions.width = options.width;
  contextOptions.height = options.height;
  contextOptions.vsync = options.vsync;
  contextOptions.debug = options.debugGl;
  auto context = createContext(backend, contextOptions);
  if (!context) return context.error();
  if (options.debugGl) gl::enableDebugOutput();
  RunSetup setup{std::move(context).value(), GameSession(game), RenderTarget{}};
  if (auto status = game.init(); !status) return status.error();
  auto target = RenderTarget::create(options.width, options.height,
                                     options.targetSamples > 0 ? options.targetSamples : options.msaa);
  if (!target) return target.error();
  setup.target = std::move(target).value();
  return setup;
}

Status writeScreenshot(const std::string& path, Game& game, const Image& frame) {
  if (!floatFormatForName(path)) return writePng(path, frame);
  auto linear = game.linearFrame();
  if (!linear) return makeError(path + ": " + linear.error().message);
  // A game that drew other views after the frame (the trade panel's comparison)
  // would hand back one of another size.
  if (linear->width != frame.width || linear->height != frame.height) {
    return makeError(path + ": the linear image is " + std::to_string(linear->width) + "x" +
                     std::to_string(linear->height) + ", the frame " + std::to_string(frame.width) + "x" +
                     std::to_string(frame.height));
  }
  return writeFloatImage(path, *linear);
}

Status finishRun(const GlContext& context, const RunOptions& options, Game& game,
                 std::vector<double> frameMs, const Image* lastFrame) {
  if (!options.benchFile.empty()) {
    BenchReport report;
    report.summary = summarize(std::move(frameMs));
    report.backend = std::string(backendName(context.backend()));
    report.renderer = context.renderer();
    report.glVersion = context.version();
    report.width = options.width;
    report.height = options.height;
    report.msaa = options.msaa;
    report.command = options.command;
    report.counters = game.frameCounters();
    if (auto s = writeBenchJson(options.benchFile, report); !s) return s;
  }
  if (!options.screenshot.empty() && lastFrame) {
    if (auto s = writeScreenshot(options.screenshot, game, *lastFrame); !s) return s;
  }
  return Ok{};
}

}  // namespace engine
