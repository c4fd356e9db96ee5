// pt_convergence: how fast the path tracer converges, measured against its own
// high-spp image. A reference at --ref-spp (seed 1000) first, then one progressive
// render (seed 1) whose samples double pass by pass; after each doubling the image
// so far is compared with the reference as 8-bit images (PSNR, as build/bin/imgdiff).
// Prints spp, seconds so far, PSNR and Mrays/s, and the time to reach 30 and 40 dB.
// The reference's own noise caps what can be measured: at --ref-spp / 4 samples it
// adds a quarter of the image's variance to the difference.
//   pt_convergence SCENE [--size WxH] [--ref-spp N] [--max-spp N] [--threads N]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asset/scene_file.h"
#include "raytrace/integrator.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"

using namespace engine;

namespace {

struct Pass {
  int spp = 0;
  double seconds = 0.0;
  double psnr = 0.0;
  double mrays = 0.0;
};

// Renders samples [first, first + count) and adds them, weighted, to `mean`.
double addSamples(const rt::RtScene& scene, rt::RenderSettings settings, int first, int count, rt::Framebuffer& mean,
                  std::uint64_t& rays) {
  settings.firstSample = first;
  settings.samplesPerPixel = count;
  const rt::RenderResult r = rt::Integrator(scene, settings).render();
  const float w = float(count) / float(first + count);
  for (std::size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += (r.image.pixels[i] - mean.pixels[i]) * w;
  rays += r.rays.total();
  return r.seconds;
}

// The first time the curve reaches `db`, interpolated in log(time) between passes.
double timeTo(const std::vector<Pass>& passes, double db) {
  for (std::size_t i = 0; i < passes.size(); ++i) {
    if (passes[i].psnr < db) continue;
    if (i == 0) return passes[0].seconds;
    const Pass& a = passes[i - 1];
    const Pass& b = passes[i];
    const double t = (db - a.psnr) / (b.psnr - a.psnr);
    return std::exp(std::log(a.seconds) + t * (std::log(b.seconds) - std::log(a.seconds)));
  }
  return -1.0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The path tracer's error against its own high-spp image, as samples accumulate.", "pt_convergence"};
  std::string scenePath, size = "320x180";
  int refSpp = 4096, maxSpp = 1024, threads = 0;
  app.add_option("scene", scenePath, "Scene file")->required();
  app.add_option("--size", size, "Image size WxH")->capture_default_str();
  app.add_option("--ref-spp", refSpp, "Samples of the reference")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  app.add_option("--max-spp", maxSpp, "Samples of the last pass")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0: every core)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  int width = 0, height = 0;
  if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width <= 0 || height <= 0) {
    std::fprintf(stderr, "pt_convergence: --size: expected WxH, got %s\n", size.c_str());
    return 2;
  }
  auto desc = loadSceneFile(scenePath);
  if (!desc) return std::fprintf(stderr, "pt_convergence: %s\n", desc.error().message.c_str()), 2;
  auto scene = rt::buildRtScene(*desc, 0.0, height);
  if (!scene) return std::fprintf(stderr, "pt_convergence: %s\n", scene.error().message.c_str()), 2;

  rt::RenderSettings settings;
  settings.method = rt::Method::Path;
  settings.width = width;
  settings.height = height;
  settings.maxDepth = 16;
  settings.threads = threads;
  settings.seed = 1000;
  rt::Framebuffer reference(width, height);
  std::uint64_t refRays = 0;
  const double refSeconds = addSamples(*scene, settings, 0, refSpp, reference, refRays);
  const Image refImage = rt::toImage(reference, scene->render());
  std::printf("# %s %dx%d, threads %d; reference %d spp in %.1f s (%.2f Mrays/s, %.0f samples/s)\n", scenePath.c_str(),
              width, height, threads, refSpp, refSeconds, double(refRays) / refSeconds / 1e6,
              double(width) * height * refSpp / refSeconds);
  std::printf("%8s %10s %8s %8s\n", "spp", "seconds", "psnr_db", "Mrays/s");

  settings.seed = 1;
  rt::Framebuffer mean(width, height);
  std::vector<Pass> passes;
  double seconds = 0.0;
  std::uint64_t rays = 0;
  for (int spp = 1, done = 0; spp <= maxSpp; spp *= 2) {
    seconds += addSamples(*scene, settings, done, spp - done, mean, rays);
    done = spp;
    auto diff = compareImages(rt::toImage(mean, scene->render()), refImage);
    if (!diff) return std::fprintf(stderr, "pt_convergence: %s\n", diff.error().message.c_str()), 2;
    passes.push_back(Pass{spp, seconds, diff->psnr, double(rays) / seconds / 1e6});
    std::printf("%8d %10.3f %8.2f %8.2f\n", spp, seconds, diff->psnr, passes.back().mrays);
    std::fflush(stdout);
  }
  for (const double db : {30.0, 40.0}) {
    const double t = timeTo(passes, db);
    if (t < 0.0) {
      std::printf("# %.0f dB: not reached by %d spp\n", db, maxSpp);
    } else {
      std::printf("# %.0f dB: %.2f s\n", db, t);
    }
  }
  return 0;
}
