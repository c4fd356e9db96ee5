#pragma once
// A one-line terminal progress bar for ray-traced renders: tiles done and the ray
// rate, redrawn on stderr at most ten times a second.
#include <chrono>

#include "raytrace/render_types.h"

namespace engine::rt {

class ProgressBar {
 public:
  // Always returns true (never cancels), so it can serve as RenderSettings::progress.
  bool update(const RenderProgress& progress);

 private:
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace engine::rt
