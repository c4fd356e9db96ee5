// imgdiff A.png B.png: compares two images (max and mean absolute difference over
// RGB, PSNR, share of pixels over a threshold) and exits 1 when over a limit.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/image.h"

int main(int argc, char** argv) {
  CLI::App app{"Compare two PNG images; exit 1 when a limit is exceeded, 2 on bad input.", "imgdiff"};
  std::string a, b, diffPath;
  std::optional<double> maxMean, minPsnr;
  std::optional<int> maxAbs;
  int threshold = 8;
  app.add_option("A", a, "First image")->required();
  app.add_option("B", b, "Second image")->required();
  app.add_option("--max-mean", maxMean, "Largest mean absolute difference allowed (0..255)");
  app.add_option("--max-abs", maxAbs, "Largest single channel difference allowed (0..255)");
  app.add_option("--min-psnr", minPsnr, "Smallest PSNR allowed, dB");
  app.add_option("--threshold", threshold, "Channel difference counted as 'over'")->capture_default_str();
  app.add_option("--diff", diffPath, "Write a difference image (x4 gain) here");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "imgdiff: %s (see --help)\n", e.what());
    return 2;
  }
  auto imageA = engine::readPng(a);
  if (!imageA) return std::fprintf(stderr, "imgdiff: %s\n", imageA.error().message.c_str()), 2;
  auto imageB = engine::readPng(b);
  if (!imageB) return std::fprintf(stderr, "imgdiff: %s\n", imageB.error().message.c_str()), 2;
  auto d = engine::compareImages(*imageA, *imageB, threshold);
  if (!d) return std::fprintf(stderr, "imgdiff: %s\n", d.error().message.c_str()), 2;
  auto ssim = engine::structuralSimilarity(*imageA, *imageB);
  if (!ssim) return std::fprintf(stderr, "imgdiff: %s\n", ssim.error().message.c_str()), 2;
  std::printf("max_abs %d mean_abs %.4f psnr %.2f over_%d %.4f%% ssim %.4f\n", d->maxAbs, d->meanAbs, d->psnr,
              threshold, d->shareOver * 100.0, *ssim);
  if (!diffPath.empty()) {
    if (auto s = engine::writePng(diffPath, engine::diffImage(*imageA, *imageB)); !s) {
      return std::fprintf(stderr, "imgdiff: %s\n", s.error().message.c_str()), 2;
    }
  }
  bool over = false;
  if (maxMean && d->meanAbs > *maxMean) over = true;
  if (maxAbs && d->maxAbs > *maxAbs) over = true;
  if (minPsnr && d->psnr < *minPsnr) over = true;
  if (over) std::printf("over the limit\n");
  return over ? 1 : 0;
}
