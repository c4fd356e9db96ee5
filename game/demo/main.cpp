// demo: the engine's showcase. Draws a scene file (assets/scenes/demo.json by
// default) in a window; with --offscreen it renders N frames at a fixed step
// through EGL or OSMesa and writes the last one to a PNG.
#include <cstdio>
#include <filesystem>

#include "app/cli.h"
#include "asset/scene_file.h"
#include "scene_game.h"

namespace {

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "demo: %s\n", message.c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Interactive OpenGL demo engine: renders a scene in a window or offscreen to PNG.", "demo"};
  engine::CommonOptions options;
  engine::SceneRenderOptions render;
  std::string scenePath;
  bool describe = false;
  app.add_option("scene", scenePath, "Scene file (JSON); default: assets/scenes/demo.json");
  engine::addCommonOptions(app, options);
  app.add_option("--supersample", render.supersampleOverride, "Render N x N times larger and average down")
      ->check(CLI::Range(1, 4));
  app.add_option("--shadow-map", render.shadowMapOverride, "Shadow map size in texels")->check(CLI::Range(64, 8192));
  app.add_option("--pcf", render.pcfKernelOverride, "PCF kernel width (odd; 1 = hard shadows)")
      ->check(CLI::IsMember({1, 3, 5, 7, 9}));
  app.add_flag("--describe", describe, "Print the passes and shader variants built for the scene");
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;

  if (options.checkDisplay) return engine::displayAvailable() ? 0 : 1;
  const bool offscreen = !options.offscreen.empty() || describe;
  if (offscreen && options.run.screenshot.empty() && !describe) {
    std::filesystem::create_directories("out");
    options.run.screenshot = "out/demo.png";
  }
  if (describe && options.offscreen.empty()) options.offscreen = "egl";
  if (auto s = engine::finishCommonOptions(options, argc, argv); !s) return fail(engine::kExitBadInput, s.error().message);
  if (scenePath.empty()) scenePath = options.assetDir + "/scenes/demo.json";

  auto scene = engine::loadSceneFile(scenePath);
  if (!scene) return fail(engine::kExitBadInput, scene.error().message);
  // The scene renderer multisamples its own HDR target; the runner's target then
  // only receives the tone-mapped result.
  render.shaderDir = options.shaderDir;
  render.msaaOverride = options.msaaGiven ? options.run.msaa : 0;
  options.run.msaa = 1;
  demo::SceneGame game(std::move(scene).value(), render);

  const engine::Backend backend = engine::chosenBackend(options);
  if (backend == engine::Backend::Window && !engine::displayAvailable()) {
    return fail(engine::kExitBadInput, "no usable display; use --offscreen to render to a PNG");
  }
  if (describe) {
    // Builds the renderer for the scene (one frame) and prints what it made.
    options.run.frames = 1;
    options.run.screenshot.clear();
    engine::Image ignored;
    const auto status = engine::runHeadless(backend, game, options.run, &ignored, [&game] {
      std::fputs(game.renderer()->describe().c_str(), stdout);
    });
    if (!status) return fail(engine::kExitBadInput, status.error().message);
    return 0;
  }
  const auto status = backend == engine::Backend::Window ? engine::runWindow(game, options.run)
                                                         : engine::runHeadless(backend, game, options.run);
  if (!status) return fail(engine::kExitBadInput, status.error().message);
  if (!options.run.screenshot.empty()) std::printf("%s\n", options.run.screenshot.c_str());
  return 0;
}
