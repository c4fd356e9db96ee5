// CDLOD terrain: selection time on the 16 km field, and the speed-accuracy table
// per screen-space error target (triangles, patches, stated geometric error and the
// measured screen-space error of the drawn surface against full resolution).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "../terrain_error.h"

using namespace engine::terrain;

namespace {

constexpr int kWidth = 1280, kHeight = 720;

Terrain& terrainOf(double size) {
  static std::unique_ptr<Terrain> t16, t4;
  std::unique_ptr<Terrain>& t = size > 8192.0 ? t16 : t4;
  if (!t) {
    TerrainSettings s;
    s.seed = 7;
    s.size = size;
    s.spacing = 1.0;
    s.heightScale = size > 8192.0 ? 1500.0 : 600.0;
    s.origin = {2.0e6, 0.0, -5.0e6};
    t = std::make_unique<Terrain>(std::move(Terrain::create(s)).value());
  }
  return *t;
}

LodCamera cameraOver(const Terrain& t, double u, double v, double above) {
  const glm::dvec3 o = t.origin();
  const glm::dvec3 eye(o.x + u, t.heightAt(o.x + u, o.z + v) + above, o.z + v);
  LodCamera c;
  c.position = eye;
  c.fovY = glm::radians(60.0);
  c.viewportHeight = kHeight;
  const glm::mat4 projection = glm::perspective(float(c.fovY), float(kWidth) / kHeight, 0.5f, 100000.0f);
  c.viewProjection = projection * glm::lookAt(glm::vec3(0.0f), glm::vec3(1.0f, -0.12f, 0.7f), glm::vec3(0, 1, 0));
  return c;
}

// Every block near enough to set the view's ranges measured first (a one-time cost
// per view, as a renderer's first frame pays it): the benchmarks time and tabulate
// the selection alone.
void measureView(const Terrain& t, const LodCamera& camera, double pixels) { measureBlocks(t, camera, pixels); }

void BM_TerrainLodSelect16km(benchmark::State& state) {
  const Terrain& t = terrainOf(16384.0);
  const LodCamera camera = cameraOver(t, 4000.0, 5000.0, 40.0);
  const double pixels = double(state.range(0)) / 10.0;
  measureView(t, camera, pixels);
  std::size_t patches = 0;
  for (auto _ : state) {
    LodSelection s = selectLod(t, camera, pixels);
    patches = s.patches.size();
    benchmark::DoNotOptimize(s.patches.data());
  }
  state.counters["patches"] = double(patches);
}
BENCHMARK(BM_TerrainLodSelect16km)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond);

// The table (4 km field so that every full-resolution sample can be checked).
void BM_TerrainLodTable4km(benchmark::State& state) {
  const Terrain& t = terrainOf(4096.0);
  const LodCamera camera = cameraOver(t, 600.0, 800.0, 30.0);
  const double pixels = double(state.range(0)) / 10.0;
  measureView(t, camera, pixels);
  LodSelection s;
  for (auto _ : state) {
    s = selectLod(t, camera, pixels);
    benchmark::DoNotOptimize(s.patches.data());
  }
  state.counters["target_px"] = pixels;
  state.counters["patches"] = double(s.stats.patches);
  state.counters["triangles"] = double(s.stats.triangles);
  state.counters["max_geom_err_m"] = s.stats.maxGeometricError;
  state.counters["max_screen_err_px"] = engine::terrain::bench::measuredScreenError(t, s, camera);
  state.counters["finest_level"] = s.stats.finestLevel;
}
BENCHMARK(BM_TerrainLodTable4km)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond)->Iterations(5);

}  // namespace
