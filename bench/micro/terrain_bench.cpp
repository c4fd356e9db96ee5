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

void BM_TerrainLodSelect16km(benchmark::State& state) {
  const Terrain& t = terrainOf(16384.0);
  const LodCamera camera = cameraOver(t, 4000.0, 5000.0, 40.0);
  const double pixels = double(state.range(0)) / 10.0;
  std::size_t patches = 0;
  for (auto _ : state) {
    LodSelection s = selectLod(t, camera, pixels);
    patches = s.patches.size();
    benchmark::DoNotOptimize(s.patches.data());
  }
  state.counters["patches"] = double(patches);
}
BENCHMARK(BM_TerrainLodSelect16km)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond);

// Largest screen-space error (pixels) of the drawn surface: at every full-resolution
// sample under a drawn triangle, the vertical gap to the true sample, projected at
// that sample's true distance.
double measuredScreenError(const Terrain& t, const LodSelection& s, const LodCamera& camera) {
  const double k = camera.viewportHeight / (2.0 * std::tan(camera.fovY / 2));
  const glm::dvec3 rel = camera.position - t.origin();
  double worst = 0.0;
  for (const LodPatch& p : s.patches) {
    const auto v = patchVertices(t, s, p);
    auto toSample = [&](const glm::vec3& x) {
      return glm::dvec3((x.x + rel.x) / t.spacing(), x.y + rel.y, (x.z + rel.z) / t.spacing());
    };
    auto tri = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
      const double area = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
      if (std::abs(area) < 1e-9) return;
      const int x0 = int(std::ceil(std::min({a.x, b.x, c.x}))), x1 = int(std::floor(std::max({a.x, b.x, c.x})));
      const int z0 = int(std::ceil(std::min({a.z, b.z, c.z}))), z1 = int(std::floor(std::max({a.z, b.z, c.z})));
      for (int z = z0; z <= z1; ++z)
        for (int x = x0; x <= x1; ++x) {
          const double w1 = ((x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z)) / area;
          const double w2 = ((b.x - a.x) * (z - a.z) - (x - a.x) * (b.z - a.z)) / area;
          const double w0 = 1.0 - w1 - w2;
          if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
          const double drawn = w0 * a.y + w1 * b.y + w2 * c.y;
          const double truth = t.sample(x, z);
          const glm::dvec3 d(x * t.spacing() - rel.x, truth - rel.y, z * t.spacing() - rel.z);
          worst = std::max(worst, std::abs(drawn - truth) * k / std::max(glm::length(d), 1e-3));
        }
    };
    const int n = kPatchQuads + 1;
    for (int j = 0; j < kPatchQuads; ++j)
      for (int i = 0; i < kPatchQuads; ++i) {
        const glm::dvec3 a = toSample(v[std::size_t(j) * n + i]), b = toSample(v[std::size_t(j) * n + i + 1]);
        const glm::dvec3 c = toSample(v[std::size_t(j + 1) * n + i + 1]), d = toSample(v[std::size_t(j + 1) * n + i]);
        tri(a, c, b);
        tri(a, d, c);
      }
  }
  return worst;
}

// The table (4 km field so that every full-resolution sample can be checked).
void BM_TerrainLodTable4km(benchmark::State& state) {
  const Terrain& t = terrainOf(4096.0);
  const LodCamera camera = cameraOver(t, 600.0, 800.0, 30.0);
  const double pixels = double(state.range(0)) / 10.0;
  LodSelection s;
  for (auto _ : state) {
    s = selectLod(t, camera, pixels);
    benchmark::DoNotOptimize(s.patches.data());
  }
  state.counters["target_px"] = pixels;
  state.counters["patches"] = double(s.stats.patches);
  state.counters["triangles"] = double(s.stats.triangles);
  state.counters["max_geom_err_m"] = s.stats.maxGeometricError;
  state.counters["max_screen_err_px"] = measuredScreenError(t, s, camera);
  state.counters["finest_level"] = s.stats.finestLevel;
}
BENCHMARK(BM_TerrainLodTable4km)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond)->Iterations(5);

}  // namespace
