#include "app/frame_stats.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

namespace engine {
namespace {

const std::chrono::steady_clock::time_point kProcessStart = std::chrono::steady_clock::now();
double firstFrameMs = -1.0;

}  // namespace

double msSinceProcessStart() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - kProcessStart).count();
}

void noteFrameFinished() {
  if (firstFrameMs < 0.0) firstFrameMs = msSinceProcessStart();
}

FrameSummary summarize(std::vector<double> frameMs) {
  FrameSummary s;
  s.frames = static_cast<int>(frameMs.size());
  if (frameMs.empty()) return s;
  std::sort(frameMs.begin(), frameMs.end());
  const size_t n = frameMs.size();
  s.medianMs = n % 2 ? frameMs[n / 2] : 0.5 * (frameMs[n / 2 - 1] + frameMs[n / 2]);
  // Nearest-rank percentile.
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * double(n)));
  s.p95Ms = frameMs[std::min(n - 1, rank == 0 ? 0 : rank - 1)];
  s.maxMs = frameMs.back();
  s.minMs = frameMs.front();
  return s;
}

Status writeBenchJson(const std::string& path, const BenchReport& r) {
  nlohmann::json j = {{"frames", r.summary.frames},
                      {"frame_ms", {{"median", r.summary.medianMs},
                                    {"p95", r.summary.p95Ms},
                                    {"max", r.summary.maxMs},
                                    {"min", r.summary.minMs}}},
                      {"backend", r.backend},
                      {"renderer", r.renderer},
                      {"gl_version", r.glVersion},
                      {"width", r.width},
                      {"height", r.height},
                      {"msaa", r.msaa},
                      {"command", r.command}};
  if (firstFrameMs >= 0.0) j["first_frame_ms_since_start"] = firstFrameMs;
  if (!r.counters.empty()) {
    nlohmann::json counters = nlohmann::json::object();
    for (const auto& [name, value] : r.counters) counters[name] = value;
    j["last_frame"] = counters;
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) return makeError(path + ": cannot write the bench report");
    out << j.dump(2) << "\n";
    if (!out) return makeError(path + ": cannot write the bench report");
  }
  std::rename(tmp.c_str(), path.c_str());
  return Ok{};
}

}  // namespace engine
