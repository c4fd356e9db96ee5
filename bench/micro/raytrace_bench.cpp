// Ray tracer throughput: Mrays/s (primary + shadow + reflection) on the course room at
// 1280 x 720, spp 1, hard (point light) and soft (area light, 4 x 4 shadow rays), with
// 1 and 2 threads; BVH build and refit of a ~10k-triangle mesh; closest-hit rays/s
// against that mesh's BVH alone.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "asset/scene_file.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"

namespace {

namespace rt = engine::rt;

// The scene files are read relative to the working folder: run from the source root,
// as the README runs every program.
engine::Result<rt::RtScene> loadCornell(bool soft) {
  auto desc = engine::loadSceneFile(soft ? "assets/scenes/cornell_soft.json" : "assets/scenes/cornell.json");
  if (!desc) return desc.error();
  return rt::analyticRtScene(*desc);
}

// args: threads, soft (0/1)
void BM_RaytraceCornell720p(benchmark::State& state) {
  const auto loaded = loadCornell(state.range(1) != 0);
  if (!loaded) {
    state.SkipWithError(loaded.error().message.c_str());
    return;
  }
  const rt::RtScene& scene = loaded.value();
  rt::RenderSettings settings;
  settings.width = 1280;
  settings.height = 720;
  settings.samplesPerPixel = 1;
  settings.shadowSamples = 4;
  settings.threads = int(state.range(0));
  std::uint64_t rays = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const rt::RenderResult r = rt::Integrator(scene, settings).render();
    rays += r.rays.total();
    seconds += r.seconds;
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  state.counters["Mrays/s"] = benchmark::Counter(double(rays) / seconds / 1e6);
  state.counters["rays/frame"] = benchmark::Counter(double(rays) / double(state.iterations()));
}
BENCHMARK(BM_RaytraceCornell720p)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->ArgNames({"threads", "soft"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A 71 x 71 vertex wavy grid: 9800 triangles, like a terrain patch or a character.
rt::RtMesh gridMesh(float phase) {
  constexpr int kSide = 71;
  rt::RtMesh mesh;
  for (int z = 0; z < kSide; ++z) {
    for (int x = 0; x < kSide; ++x) {
      mesh.positions.emplace_back(x * 0.1f, std::sin(x * 0.3f + phase) * std::cos(z * 0.2f), z * 0.1f);
    }
  }
  for (int z = 0; z + 1 < kSide; ++z) {
    for (int x = 0; x + 1 < kSide; ++x) {
      const auto i = std::uint32_t(z * kSide + x);
      mesh.indices.insert(mesh.indices.end(), {i, i + kSide, i + 1, i + 1, i + kSide, i + kSide + 1});
    }
  }
  return mesh;
}

void BM_BvhBuild10k(benchmark::State& state) {
  rt::RtScene scene;
  (void)scene.addMesh(gridMesh(0.0f));
  for (auto _ : state) benchmark::DoNotOptimize(scene.build());
  state.counters["triangles"] = double(scene.triangleCount());
}
BENCHMARK(BM_BvhBuild10k)->Unit(benchmark::kMillisecond);

void BM_BvhRefit10k(benchmark::State& state) {
  rt::RtScene scene;
  auto id = scene.addMesh(gridMesh(0.0f));
  scene.build();
  const rt::RtMesh moved = gridMesh(0.5f);
  for (auto _ : state) {
    (void)scene.updateMesh(*id, moved.positions);
    benchmark::DoNotOptimize(scene.refit());
  }
}
BENCHMARK(BM_BvhRefit10k)->Unit(benchmark::kMicrosecond);

// Closest-hit rays from above at random points of the 10k-triangle grid: the BVH's
// own speed, single-threaded (the yardstick for an Embree comparison).
void BM_BvhClosestHit10k(benchmark::State& state) {
  rt::RtScene scene;
  (void)scene.addMesh(gridMesh(0.0f));
  scene.build();
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 7.0f), d(-0.3f, 0.3f);
  std::vector<rt::Ray<float>> rays;
  for (int i = 0; i < 4096; ++i) {
    rays.push_back({glm::vec3(u(rng), 3.0f, u(rng)), glm::normalize(glm::vec3(d(rng), -1.0f, d(rng)))});
  }
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    hits += scene.bvh().intersect(rays[i++ & 4095]).has_value();
  }
  benchmark::DoNotOptimize(hits);
  state.counters["Mrays/s"] = benchmark::Counter(double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BvhClosestHit10k);

// demo.json's four characters, per frame: pose + CPU skinning, then either a refit of
// each character's own BVH (what AnimatedRtScene::setTime does) or a full SAH build of
// it. The static world (terrain, boxes: group 0) is built once, before the loop; its
// build time is reported as static_build_ms. Per character: cN_* in ms per frame.
void demoCharacters(benchmark::State& state, bool rebuild) {
  auto desc = engine::loadSceneFile("assets/scenes/demo.json");
  if (!desc) {
    state.SkipWithError(desc.error().message.c_str());
    return;
  }
  rt::SceneBuildStats created;
  auto animated = rt::AnimatedRtScene::create(*desc, 1.0, 720, &created);
  if (!animated) {
    state.SkipWithError(animated.error().message.c_str());
    return;
  }
  const std::size_t characters = created.instances.size();
  std::vector<double> skin(characters), bvh(characters);
  double t = 1.0;
  for (auto _ : state) {
    t += 1.0 / 30.0;
    rt::SceneBuildStats frame;
    if (!animated->setTime(t, &frame)) {
      state.SkipWithError("setTime failed");
      return;
    }
    for (std::size_t c = 0; c < characters; ++c) {
      skin[c] += frame.instances[c].skinSeconds;
      // Groups are made in the scene file's order, after the static world's group 0.
      bvh[c] += rebuild ? animated->scene().buildGroup(int(c) + 1) : frame.instances[c].bvhSeconds;
    }
  }
  const double n = double(state.iterations());
  double total = 0.0;
  for (std::size_t c = 0; c < characters; ++c) {
    // Appended, not "c" + to_string(c): g++ 12 -O3 warns falsely (-Wrestrict) on that.
    std::string name = "c";
    name += std::to_string(c);
    state.counters[name + "_tris"] = double(created.instances[c].triangles);
    state.counters[name + "_skin_ms"] = 1e3 * skin[c] / n;
    state.counters[name + (rebuild ? "_build_ms" : "_refit_ms")] = 1e3 * bvh[c] / n;
    total += bvh[c] / n;
  }
  state.counters[rebuild ? "bvh_build_ms/frame" : "bvh_refit_ms/frame"] = 1e3 * total;
  state.counters["static_build_ms"] = 1e3 * (created.bvhSeconds - [&] {
    double s = 0.0;
    for (const auto& i : created.instances) s += i.bvhSeconds;
    return s;
  }());
}

void BM_DemoCharactersRefit(benchmark::State& state) { demoCharacters(state, false); }
void BM_DemoCharactersRebuild(benchmark::State& state) { demoCharacters(state, true); }
BENCHMARK(BM_DemoCharactersRefit)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DemoCharactersRebuild)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
