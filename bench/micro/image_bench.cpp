// Image comparison cost: golden tests and the trade-off tables compare many frames.
#include <benchmark/benchmark.h>

#include "core/image.h"

static void BM_CompareImages720p(benchmark::State& state) {
  engine::Image a(1280, 720), b(1280, 720);
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    a.pixels[i] = static_cast<std::uint8_t>(i * 7);
    b.pixels[i] = static_cast<std::uint8_t>(i * 7 + (i % 13 == 0));
  }
  for (auto _ : state) {
    auto d = engine::compareImages(a, b);
    benchmark::DoNotOptimize(d);
  }
  state.SetItemsProcessed(state.iterations() * 1280 * 720);
}
BENCHMARK(BM_CompareImages720p)->Unit(benchmark::kMillisecond);
