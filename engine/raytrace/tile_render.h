#pragma once
// What the Whitted and the path tracer share about covering an image: the strata of a
// pixel's samples, and the parallel loop over tiles with its progress and ray counts.
// Internal to the ray tracer (whitted_tracer.cpp, path_tracer.cpp) and the GPU tracer.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "raytrace/render_types.h"
#include "raytrace/rng.h"

namespace engine::rt::detail {

// Splits N samples into an sx x sy grid with sx the largest divisor of N not above
// sqrt(N): 4 -> 2 x 2, 8 -> 2 x 4, 7 -> 1 x 7.
inline glm::ivec2 strataFor(int n) {
  int sx = std::max(1, int(std::sqrt(double(n))));
  while (n % sx != 0) --sx;
  return {sx, n / sx};
}

// Where the Whitted tracer puts a pixel's samples: stratum (i, j) of the strataFor
// grid, jittered by two draws from the pixel's stream, x's first. The scalar tracer
// and its packets both place them here, so that they draw the same streams alike.
class PixelStrata {
 public:
  explicit PixelStrata(int samples)
      : count_(strataFor(std::max(1, samples))), inverseX_(exactInverse(count_.x)), inverseY_(exactInverse(count_.y)) {}

  glm::ivec2 count() const { return count_; }
  // The image point of stratum (i, j) of pixel (x, y).
  glm::dvec2 point(int x, int y, int i, int j, Pcg32& rng) const {
    const double u = i + double(rng.uniform());
    const double v = j + double(rng.uniform());
    return {x + along(u, count_.x, inverseX_), y + along(v, count_.y, inverseY_)};
  }

 private:
  // s / n, as a multiply by 1 / n where n is a power of two (exact, the same bits,
  // without the division's latency on the stream's chain).
  static double along(double s, int n, double inverse) { return inverse > 0.0 ? s * inverse : s / n; }
  static double exactInverse(int n) { return (n & (n - 1)) == 0 ? 1.0 / n : 0.0; }

  glm::ivec2 count_;
  double inverseX_, inverseY_;  // 1 / count where that is exact, else 0
};

struct AtomicCounters {
  std::atomic<std::uint64_t> primary{0}, shadow{0}, reflection{0};

  void add(const RayCounters& c) {
    primary.fetch_add(c.primary, std::memory_order_relaxed);
    shadow.fetch_add(c.shadow, std::memory_order_relaxed);
    reflection.fetch_add(c.reflection, std::memory_order_relaxed);
  }
  RayCounters load() const {
    return RayCounters{primary.load(std::memory_order_relaxed), shadow.load(std::memory_order_relaxed),
                       reflection.load(std::memory_order_relaxed)};
  }
};

// TBB rather than std::thread or OpenMP: its work stealing balances tiles of very
// different cost (a mirror tile traces six times the rays of a wall tile), it is a
// Debian package the project already uses, and it needs no compiler flag. The image
// does not depend on the schedule: each pixel's (or sample's) RNG is seeded from its
// coordinates and the seed alone (rng.h), and each pixel is written by exactly one tile.
// `tracer`: anything with renderPixel(x, y, RayCounters&) const, safe to call from
// several threads at once; or renderSpan(x0, x1, y, glm::vec3* out, RayCounters&),
// the pixels of a tile's row at once.
template <typename Tracer>
RenderResult renderTiles(const Tracer& tracer, const RenderSettings& settings) {
  RenderResult result;
  result.image = Framebuffer(settings.width, settings.height);
  // The clock starts once the image is allocated, as the naive tracer's does
  // (bench/course_room_vs_naive): its first touch is the kernel's, not the tracer's.
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const int tile = std::max(1, settings.tileSize);
  const int tilesX = (settings.width + tile - 1) / tile;
  const int tilesY = (settings.height + tile - 1) / tile;
  const int tilesTotal = tilesX * tilesY;
  AtomicCounters counters;
  std::atomic<int> tilesDone{0};
  std::atomic<bool> cancelled{false};
  std::mutex progressMutex;

  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) {
    limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(settings.threads));
  }
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tilesTotal, 1),
      [&](const tbb::blocked_range<int>& range) {
        for (int t = range.begin(); t != range.end(); ++t) {
          if (cancelled.load(std::memory_order_relaxed)) return;
          const int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
          const int x1 = std::min(x0 + tile, settings.width), y1 = std::min(y0 + tile, settings.height);
          RayCounters local;
          for (int y = y0; y < y1; ++y) {
            if constexpr (requires(glm::vec3* out) { tracer.renderSpan(x0, x1, y, out, local); }) {
              tracer.renderSpan(x0, x1, y, &result.image.at(x0, y), local);
            } else {
              for (int x = x0; x < x1; ++x) result.image.at(x, y) = tracer.renderPixel(x, y, local);
            }
          }
          counters.add(local);
          const int done = tilesDone.fetch_add(1) + 1;
          if (settings.progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            if (!settings.progress(RenderProgress{done, tilesTotal, counters.load(), elapsed()})) {
              cancelled.store(true);
            }
          }
        }
      },
      tbb::simple_partitioner());
  result.rays = counters.load();
  result.seconds = elapsed();
  result.cancelled = cancelled.load();
  return result;
}

}  // namespace engine::rt::detail
