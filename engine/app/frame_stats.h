#pragma once
// Frame times of a run, summarised as median / p95 / max and written as JSON for
// `--bench`. Medians, not means: these machines are noisy.
#include <string>
#include <utility>
#include <vector>

#include "core/result.h"

namespace engine {

struct FrameSummary {
  int frames = 0;
  double medianMs = 0.0;
  double p95Ms = 0.0;
  double maxMs = 0.0;
  double minMs = 0.0;
};

FrameSummary summarize(std::vector<double> frameMs);

struct BenchReport {
  FrameSummary summary;
  std::string backend;
  std::string renderer;
  std::string glVersion;
  int width = 0;
  int height = 0;
  int msaa = 1;
  std::string command;
  // Work done by the last frame, by name (draw calls, program changes, triangles).
  std::vector<std::pair<std::string, double>> counters;
};

Status writeBenchJson(const std::string& path, const BenchReport& report);

// Milliseconds from the process's start (the engine's static initialisation, before
// main) to now.
double msSinceProcessStart();
// The runners call this when a frame is finished (glFinish, or the window's swap):
// the first call is kept, and a bench report then says how long starting, loading
// and drawing the first frame took ("first_frame_ms_since_start"), what a user waits
// for after typing the command.
void noteFrameFinished();

}  // namespace engine
