// The GPU ray tracer (engine/gputrace) against the CPU's, in one run, on the same
// scene, size and samples:
//  - Whitted and path tracer: Integrator::render (TBB, every core) and
//    GpuTracer::render, rays per second as each counts them (the same rays: the
//    GpuWhitted and GpuPath tests hold the counts equal; the path tracer's row prints
//    both). The GPU's time is the dispatch to glFinish; its first run, which includes
//    the driver's compile of the kernel, is reported apart and left out.
//  - Ray queries on a triangle scene (--queries, default demo.json: terrain and
//    characters): the camera's primary rays, closest hit and any hit each, through
//    RtScene on every core and through GpuTracer::trace (upload and read-back
//    included) with both GPU layouts, the CPU's 8-wide nodes and the 4-wide ones.
// Medians of --runs runs, and the ratio GPU / CPU.
//
//   build/bin/gpu_trace [--runs N] [--size WxH] [--spp N] [--pt-spp N] [--offscreen egl|osmesa]
//                       [--queries scene.json] [scene.json ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <tbb/parallel_for.h>

#include "app/cli.h"
#include "asset/scene_file.h"
#include "gputrace/gpu_tracer.h"
#include "platform/gl_context.h"
#include "raytrace/camera.h"
#include "raytrace/integrator.h"
#include "raytrace/scene_builder.h"

namespace {

namespace rt = engine::rt;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

int fail(const std::string& message) {
  std::fprintf(stderr, "gpu_trace: %s\n", message.c_str());
  return engine::kExitBadInput;
}

struct Options {
  int runs = 5;
  int spp = 1;
  int pathSpp = 1;
  int shadowSamples = 4;
  std::string queries;
  std::vector<std::string> scenes;
};

// One integrator on one scene, CPU against GPU: a row of the table.
engine::Status benchRender(const std::string& path, const Options& o, rt::Method method, int width, int height,
                           const std::string& shaderDir) {
  auto desc = engine::loadSceneFile(path);
  if (!desc) return desc.error();
  auto scene = rt::buildRtScene(*desc, 0.0, height);
  if (!scene) return scene.error();
  const bool pathTraced = method == rt::Method::Path;
  rt::RenderSettings settings;
  settings.method = method;
  settings.width = width;
  settings.height = height;
  settings.samplesPerPixel = pathTraced ? o.pathSpp : o.spp;
  settings.shadowSamples = o.shadowSamples;
  if (pathTraced) settings.maxDepth = 16;  // demo --mode pathtrace's default
  if (const std::string why = engine::gpurt::unsupported(*scene, settings); !why.empty()) {
    return engine::makeError(path + ": --device gpu: " + why);
  }
  auto tracer = engine::gpurt::GpuTracer::create(*scene, shaderDir);
  if (!tracer) return tracer.error();
  auto first = tracer->render(settings);
  if (!first) return first.error();
  std::vector<double> cpu, gpu;
  rt::RayCounters cpuRays, gpuRays;
  for (int i = 0; i < o.runs; ++i) {
    const rt::RenderResult c = rt::Integrator(*scene, settings).render();
    cpu.push_back(double(c.rays.total()) / c.seconds / 1e6);
    auto g = tracer->render(settings);
    if (!g) return g.error();
    gpu.push_back(double(g->rays.total()) / g->seconds / 1e6);
    cpuRays = c.rays;
    gpuRays = g->rays;
  }
  const double cpuM = median(cpu), gpuM = median(gpu);
  std::printf("%s %s %dx%d spp %d: %llu rays (CPU %llu); CPU %.2f Mrays/s, GPU %.2f Mrays/s (first run, compile "
              "included: %.2f s), GPU / CPU %.2f\n",
              pathTraced ? "pathtrace" : "whitted", path.c_str(), width, height, settings.samplesPerPixel,
              (unsigned long long)gpuRays.total(), (unsigned long long)cpuRays.total(), cpuM, gpuM, first->seconds,
              gpuM / cpuM);
  return engine::Ok{};
}

engine::Status benchQueries(const std::string& path, const Options& o, int width, int height, const std::string& shaderDir) {
  auto desc = engine::loadSceneFile(path);
  if (!desc) return desc.error();
  auto scene = rt::buildRtScene(*desc, 0.0, height);
  if (!scene) return scene.error();
  const rt::PinholeCamera camera(scene->camera(), width, height);
  std::vector<rt::Ray<float>> rays;
  std::vector<engine::gpurt::RayQuery> queries;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const rt::Ray<float> r = camera.clippedToFarPlane(camera.generateRay<float>(x + 0.5, y + 0.5));
      rays.push_back(r);
      queries.push_back({glm::vec4(r.o, r.tMax), glm::vec4(r.d, 0.0f)});
    }
  }
  auto tracer = engine::gpurt::GpuTracer::create(*scene, shaderDir, 8);
  if (!tracer) return tracer.error();
  auto tracer4 = engine::gpurt::GpuTracer::create(*scene, shaderDir, 4);
  if (!tracer4) return tracer4.error();
  (void)tracer->trace(queries);  // the compiles
  (void)tracer4->trace(queries);
  std::vector<double> cpu, gpu, gpu4;
  std::vector<int> hit(rays.size());
  for (int i = 0; i < o.runs; ++i) {
    auto start = Clock::now();
    tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t k) {
      hit[k] = scene->intersect(rays[k]) ? 1 : 0;
      hit[k] += scene->intersectAny(rays[k]) ? 1 : 0;
    });
    cpu.push_back(2.0 * double(rays.size()) / std::chrono::duration<double>(Clock::now() - start).count() / 1e6);
    start = Clock::now();
    (void)tracer->trace(queries);
    gpu.push_back(2.0 * double(rays.size()) / std::chrono::duration<double>(Clock::now() - start).count() / 1e6);
    start = Clock::now();
    (void)tracer4->trace(queries);
    gpu4.push_back(2.0 * double(rays.size()) / std::chrono::duration<double>(Clock::now() - start).count() / 1e6);
  }
  const double cpuM = median(cpu), gpuM = median(gpu), gpu4M = median(gpu4);
  std::printf("queries %s %dx%d: %zu triangles, %zu closest + any-hit pairs; CPU %.2f Mrays/s, GPU BVH8 %.2f Mrays/s "
              "(GPU / CPU %.2f), GPU BVH4 %.2f Mrays/s (BVH4 / BVH8 %.2f)\n",
              path.c_str(), width, height, scene->triangleCount(), rays.size(), cpuM, gpuM, gpuM / cpuM, gpu4M, gpu4M / gpuM);
  return engine::Ok{};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The GPU ray tracer against the CPU's: Whitted and path-traced images and ray queries, Mrays/s.",
               "gpu_trace"};
  engine::CommonOptions common;
  Options o;
  app.add_option("scenes", o.scenes, "Whitted and path-traced scenes (default: cornell.json cornell_soft.json; 'none' skips)");
  app.add_option("--runs", o.runs, "Runs per measurement (median)")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--spp", o.spp, "Whitted samples per pixel")->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--pt-spp", o.pathSpp, "Path tracer samples per pixel")->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--shadow-samples", o.shadowSamples, "N x N shadow rays per area light")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--queries", o.queries, "Triangle scene for the ray queries (default demo.json; 'none' skips)");
  engine::addCommonOptions(app, common);
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;
  if (common.offscreen.empty()) common.offscreen = "egl";
  if (auto s = engine::finishCommonOptions(common, argc, argv); !s) return fail(s.error().message);
  // Line by line, also into a file: a run stopped by a timeout keeps what it measured.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (o.scenes == std::vector<std::string>{"none"}) {
    o.scenes.clear();
  } else if (o.scenes.empty()) {
    o.scenes = {common.assetDir + "/scenes/cornell.json", common.assetDir + "/scenes/cornell_soft.json"};
  }
  if (o.queries.empty()) o.queries = common.assetDir + "/scenes/demo.json";
  engine::ContextOptions context;
  context.width = 16;
  context.height = 16;
  auto gl = engine::createContext(engine::chosenBackend(common), context);
  if (!gl) return fail(gl.error().message);
  std::printf("%s\n", common.run.command.c_str());
  for (const rt::Method method : {rt::Method::Whitted, rt::Method::Path}) {
    for (const std::string& scene : o.scenes) {
      if (auto s = benchRender(scene, o, method, common.run.width, common.run.height, common.shaderDir); !s)
        return fail(s.error().message);
    }
  }
  if (o.queries != "none") {
    if (auto s = benchQueries(o.queries, o, common.run.width, common.run.height, common.shaderDir); !s) return fail(s.error().message);
  }
  return 0;
}
