// demo: the engine's showcase. In a window by default; with --offscreen it renders
// N frames at a fixed step through EGL or OSMesa and writes the last one to a PNG.
#include <cstdio>
#include <filesystem>

#include "app/cli.h"
#include "procedural_scene.h"

namespace {

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "demo: %s\n", message.c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Interactive OpenGL demo engine: renders a scene in a window or offscreen to PNG.",
               "demo"};
  engine::CommonOptions options;
  std::string scenePath;
  app.add_option("scene", scenePath, "Scene file (JSON); the built-in scene when omitted");
  engine::addCommonOptions(app, options);
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;

  if (options.checkDisplay) return engine::displayAvailable() ? 0 : 1;
  const bool offscreen = !options.offscreen.empty();
  if (offscreen && options.run.screenshot.empty()) {
    std::filesystem::create_directories("out");
    options.run.screenshot = "out/demo.png";
  }
  if (auto s = engine::finishCommonOptions(options, argc, argv); !s) {
    return fail(engine::kExitBadInput, s.error().message);
  }

  auto settings = scenePath.empty() ? engine::Result<demo::SceneSettings>(demo::defaultSceneSettings())
                                    : demo::loadSceneSettings(scenePath);
  if (!settings) return fail(engine::kExitBadInput, settings.error().message);

  demo::ProceduralScene scene(options.shaderDir, options.assetDir, std::move(settings).value());
  const engine::Backend backend = engine::chosenBackend(options);
  if (backend == engine::Backend::Window && !engine::displayAvailable()) {
    return fail(engine::kExitBadInput, "no usable display; use --offscreen to render to a PNG");
  }
  const auto status = backend == engine::Backend::Window
                          ? engine::runWindow(scene, options.run)
                          : engine::runHeadless(backend, scene, options.run);
  if (!status) return fail(engine::kExitFailure, status.error().message);
  if (!options.run.screenshot.empty()) std::printf("%s\n", options.run.screenshot.c_str());
  return 0;
}
