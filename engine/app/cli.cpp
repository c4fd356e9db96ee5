#include "app/cli.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "core/float_image_io.h"

namespace engine {

void addCommonOptions(CLI::App& app, CommonOptions& o) {
  app.add_option("--offscreen", o.offscreen,
                 "Render without a window through egl (default) or osmesa")
      ->expected(0, 1)
      ->default_str("egl")
      ->check(CLI::IsMember({"egl", "osmesa"}));
  app.add_option("--size", o.size, "Frame size WxH")->capture_default_str();
  app.add_option("--time", o.run.time, "Scene time of the captured frame, seconds");
  app.add_option("--dt", o.run.dt, "Fixed simulation step, seconds")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 10.0));
  app.add_option("--frames", o.frames,
                 "Frames to run at the fixed step, the last one at --time (default: 1 "
                 "offscreen; in a window, until it is closed)")
      ->check(CLI::Range(0, 10000000));
  app.add_option("--screenshot", o.run.screenshot,
                 "Write the last frame to this file: .png as shown, .exr or .pfm its linear radiance (float, before "
                 "exposure, tone map and output curve)");
  app.add_flag("--screenshot-window", o.run.screenshotWindow,
               "Window with --frames: the screenshot is the whole window, its panel included");
  app.add_option("--msaa", o.msaa, "Multisample anti-aliasing samples (default 1)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  app.add_option("--bench", o.run.benchFile,
                 "Write frame-time median, p95 and max to this JSON file");
  app.add_option("--shaders", o.shaderDir, "Folder of the GLSL sources");
  app.add_option("--assets", o.assetDir, "Folder of the shipped assets (models, scenes)");
  app.add_flag("--no-vsync", [&o](std::int64_t) { o.run.vsync = false; }, "Window: do not wait for vsync");
  app.add_flag("--debug-gl", o.run.debugGl, "Turn on GL debug output (KHR_debug)");
  app.add_flag("--check-display", o.checkDisplay, "Exit 0 when a window can be opened here")
      ->group("");
}

Status checkWritable(const std::string& path, const std::string& what) {
  const std::string probe = path + ".tmp";
  {
    std::ofstream out(probe, std::ios::binary);
    if (!out) {
      return makeError(what + " " + path + ": cannot write there (is the folder there and writable?)");
    }
  }
  std::remove(probe.c_str());
  return Ok{};
}

Status checkScreenshotName(const std::string& path, bool wholeWindow) {
  const bool linear = floatFormatForName(path).has_value();
  if (!linear && lowerCaseExtension(path) != ".png") {
    return makeError("--screenshot " + path + ": the name must end in .png (the frame as shown), .exr or .pfm (its "
                     "linear radiance)");
  }
  if (linear && wholeWindow) {
    return makeError("--screenshot-window --screenshot " + path + ": the whole window (panel included) exists only "
                     "as display values; write it as .png");
  }
  return Ok{};
}

Status finishCommonOptions(CommonOptions& o, int argc, char** argv) {
  static const std::regex sizeRe(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(o.size, m, sizeRe)) {
    return makeError("--size " + o.size + ": expected WIDTHxHEIGHT, e.g. 1280x720");
  }
  o.run.width = std::stoi(m[1].str());
  o.run.height = std::stoi(m[2].str());
  if (o.run.width < 1 || o.run.height < 1 || o.run.width > 16384 || o.run.height > 16384) {
    return makeError("--size " + o.size + ": each side must be within 1..16384");
  }
  if (o.run.time && !std::isfinite(*o.run.time)) return makeError("--time: must be a finite number");
  o.run.frames = o.frames.value_or(o.offscreen.empty() ? 0 : 1);
  o.run.msaa = o.msaa.value_or(1);
  o.msaaGiven = o.msaa.has_value();
  if (o.run.frames == 0 && !o.offscreen.empty()) {
    return makeError("--frames 0 (run until closed) only makes sense in a window");
  }
  if (o.shaderDir.empty()) {
    const char* env = std::getenv("ENGINE_SHADER_DIR");
    o.shaderDir = env ? env : ENGINE_DEFAULT_SHADER_DIR;
  }
  if (!std::filesystem::is_directory(o.shaderDir)) {
    return makeError("shader folder " + o.shaderDir + " not found (use --shaders DIR)");
  }
  if (o.assetDir.empty()) {
    const char* env = std::getenv("ENGINE_ASSET_DIR");
    o.assetDir = env ? env : ENGINE_DEFAULT_ASSET_DIR;
  }
  if (!o.run.screenshot.empty()) {
    if (auto s = checkScreenshotName(o.run.screenshot, o.run.screenshotWindow); !s) return s;
    if (auto s = checkWritable(o.run.screenshot, "--screenshot"); !s) return s;
  }
  if (!o.run.benchFile.empty()) {
    if (auto s = checkWritable(o.run.benchFile, "--bench"); !s) return s;
  }
  for (int i = 0; i < argc; ++i) o.run.command += (i ? " " : "") + std::string(argv[i]);
  return Ok{};
}

Backend chosenBackend(const CommonOptions& o) {
  if (o.offscreen.empty()) return Backend::Window;
  return *parseBackend(o.offscreen);
}

std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s (see --help)\n", app.get_name().c_str(), e.what());
    return kExitBadInput;
  }
  return std::nullopt;
}

}  // namespace engine
