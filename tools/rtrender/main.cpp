// rtrender: renders a scene file (assets/scenes/*.json) with the CPU ray tracer.
//   rtrender SCENE.json [--size WxH] [--spp N] [--shadow-samples N] [--max-depth N]
//            [--threads N] [--seed N] [--rt-precision float|double] [--out F.png]
// A progress bar with the ray rate goes to stderr; the summary (time, rays, Mrays/s)
// to stdout. Exit codes: 0 written; 2 bad options, scene file or output path.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "asset/scene_file.h"
#include "core/image.h"
#include "raytrace/integrator.h"
#include "raytrace/progress_bar.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kMaxSide = 16384;

struct Options {
  std::string scene;
  std::string size = "640x480";
  int spp = 1;
  int shadowSamples = 4;
  int maxDepth = 5;
  int threads = 0;
  std::uint64_t seed = 1;
  std::string precision = "float";
  std::string out = "out/rtrender.png";
  double time = 0.0;
};

bool parseSize(const std::string& text, int& w, int& h) {
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%dx%d%n", &w, &h, &consumed) != 2 || consumed != int(text.size())) return false;
  return w > 0 && h > 0 && w <= kMaxSide && h <= kMaxSide;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Renders a scene file with the CPU ray tracer into a PNG."};
  Options o;
  app.add_option("scene", o.scene, "scene file (JSON)")->required();
  app.add_option("--size", o.size, "image size WxH")->capture_default_str();
  app.add_option("--spp", o.spp, "stratified samples per pixel")->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--shadow-samples", o.shadowSamples, "N: N x N shadow rays per area light")
      ->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--max-depth", o.maxDepth, "mirror recursion depth")->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--threads", o.threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024))->capture_default_str();
  app.add_option("--seed", o.seed, "random seed")->capture_default_str();
  app.add_option("--rt-precision", o.precision, "float or double")
      ->check(CLI::IsMember({"float", "double"}))->capture_default_str();
  app.add_option("--out", o.out, "output PNG")->capture_default_str();
  app.add_option("--time", o.time, "scene time in seconds (poses the scene's models)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "rtrender: %s\n", e.what());
    return kExitBadInput;
  }
  engine::rt::RenderSettings settings;
  if (!parseSize(o.size, settings.width, settings.height)) {
    std::fprintf(stderr, "rtrender: --size: expected WxH with sides 1..%d, got \"%s\"\n", kMaxSide, o.size.c_str());
    return kExitBadInput;
  }
  // Refuse a missing output folder before a long render, not after it.
  const std::filesystem::path outFolder = std::filesystem::path(o.out).parent_path();
  if (!outFolder.empty() && !std::filesystem::is_directory(outFolder)) {
    std::fprintf(stderr, "rtrender: --out: no folder %s\n", outFolder.string().c_str());
    return kExitBadInput;
  }
  auto desc = engine::loadSceneFile(o.scene);
  if (!desc) {
    std::fprintf(stderr, "rtrender: %s\n", desc.error().message.c_str());
    return kExitBadInput;
  }
  settings.samplesPerPixel = o.spp;
  settings.shadowSamples = o.shadowSamples;
  settings.maxDepth = o.maxDepth;
  settings.threads = o.threads;
  settings.seed = o.seed;
  settings.precision = o.precision == "double" ? engine::rt::Precision::Double : engine::rt::Precision::Float;
  engine::rt::ProgressBar bar;
  settings.progress = [&bar](const engine::rt::RenderProgress& p) { return bar.update(p); };

  auto run = engine::rt::raytraceScene(*desc, o.time, settings);
  if (!run) {
    std::fprintf(stderr, "rtrender: %s\n", run.error().message.c_str());
    return kExitBadInput;
  }
  const engine::rt::RenderResult& result = run->result;
  if (auto written = engine::writePng(o.out, run->image); !written) {
    std::fprintf(stderr, "rtrender: %s\n", written.error().message.c_str());
    return kExitBadInput;
  }
  const engine::rt::RayCounters& r = result.rays;
  std::printf("%s: %dx%d spp %d, %.3f s, %llu rays (%llu primary, %llu shadow, %llu reflection), %.2f Mrays/s\n",
              o.out.c_str(), settings.width, settings.height, settings.samplesPerPixel, result.seconds,
              static_cast<unsigned long long>(r.total()), static_cast<unsigned long long>(r.primary),
              static_cast<unsigned long long>(r.shadow), static_cast<unsigned long long>(r.reflection),
              result.seconds > 0.0 ? double(r.total()) / result.seconds / 1e6 : 0.0);
  return 0;
}
