#pragma once
// Command-line pieces every program shares (demo, viewer): the run options
// (--offscreen, --size, --time, --dt, --frames, --screenshot, --msaa, --bench), parsed
// with CLI11, and the checks that turn bad values into one clear line and exit 2.
#include <optional>
#include <string>

#include "app/runner.h"

// Forward-declared: CLI11 is header-only and costs about 7 s of compile per file that
// includes it, so only the files that build an App (the programs' mains, cli.cpp)
// include <CLI/CLI.hpp>.
namespace CLI {
class App;
}

namespace engine {

struct CommonOptions {
  RunOptions run;
  std::string offscreen;     // "", "egl" or "osmesa"
  std::string size = "1280x720";
  std::optional<int> frames;  // default: 1 offscreen, 0 (until closed) in a window
  std::optional<int> msaa;    // default 1
  bool msaaGiven = false;
  std::string shaderDir;     // default: the source tree's shaders/
  std::string assetDir;      // default: the source tree's assets/
  bool checkDisplay = false; // exit 0 when a window can be opened, 1 otherwise
};

// Adds the shared options to `app`.
void addCommonOptions(CLI::App& app, CommonOptions& options);
// Validates and completes the options after parsing (size, shader folder, output
// folder writable); the error is one line for the user.
Status finishCommonOptions(CommonOptions& options, int argc, char** argv);

// The backend the options ask for: Window unless --offscreen was given.
Backend chosenBackend(const CommonOptions& options);

// --screenshot's name picks its format: .png, or .exr / .pfm for the linear image
// (core/float_image_io.h); any other name, or a float format for the whole window
// (--screenshot-window), is an error.
Status checkScreenshotName(const std::string& path, bool wholeWindow);

// Checks that `path` can be written without leaving anything behind.
Status checkWritable(const std::string& path, const std::string& what);

// Exit codes: 0 ok, 1 a failure inside the engine, 2 bad input (options, files,
// paths) or no display without --offscreen.
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

// Runs `parse` and maps CLI11's outcomes to our exit codes; returns nullopt when the
// program should go on.
std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv);

}  // namespace engine
