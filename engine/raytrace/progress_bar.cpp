#include "raytrace/progress_bar.h"

#include <cstdio>

namespace engine::rt {

bool ProgressBar::update(const RenderProgress& p) {
  const auto now = std::chrono::steady_clock::now();
  if (p.tilesDone != p.tilesTotal && now - last_ < std::chrono::milliseconds(100)) return true;
  last_ = now;
  constexpr int kWidth = 40;
  const int filled = p.tilesTotal > 0 ? kWidth * p.tilesDone / p.tilesTotal : kWidth;
  const double rate = p.seconds > 0.0 ? double(p.rays.total()) / p.seconds / 1e6 : 0.0;
  std::fprintf(stderr, "\r[%.*s%*s] %3d%% %7.2f Mrays/s", filled, "########################################",
               kWidth - filled, "", p.tilesTotal > 0 ? 100 * p.tilesDone / p.tilesTotal : 100, rate);
  if (p.tilesDone == p.tilesTotal) std::fputc('\n', stderr);
  std::fflush(stderr);
  return true;
}

}  // namespace engine::rt
