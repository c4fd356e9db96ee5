#include "progressive_trace.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "app/game.h"
#include "raytrace/progress_bar.h"
#include "raytrace/tone_map.h"

namespace demo {
namespace {
constexpr int kTile = 16;
}

void showTracedImage(const engine::gl::Framebuffer& image, int width, int height, const engine::FrameInfo& frame) {
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  // Encoded display values: copied as they are, flipped.
  glDisable(GL_FRAMEBUFFER_SRGB);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBlitNamedFramebuffer(image.id(), GLuint(target), 0, 0, width, height, 0, frame.height, frame.width, 0,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

engine::Result<std::unique_ptr<ProgressiveTrace>> ProgressiveTrace::start(std::unique_ptr<engine::rt::RtScene> scene,
                                                                         const engine::rt::RenderSettings& settings,
                                                                         bool progressBar) {
  std::unique_ptr<ProgressiveTrace> t(new ProgressiveTrace());
  t->scene_ = std::move(scene);
  t->settings_ = settings;
  t->progressBar_ = progressBar;
  t->integrator_ = std::make_unique<engine::rt::Integrator>(*t->scene_, t->settings_);
  t->tilesX_ = (settings.width + kTile - 1) / kTile;
  t->tilesY_ = (settings.height + kTile - 1) / kTile;
  const size_t tiles = size_t(t->tilesX_ * t->tilesY_);
  t->tilePasses_ = std::make_unique<std::atomic<int>[]>(tiles);
  t->tileUploaded_.assign(tiles, 0);
  t->tileLocks_ = std::make_unique<std::mutex[]>(tiles);
  t->pixels_.assign(size_t(settings.width) * size_t(settings.height) * 4, 0);
  t->sum_.assign(size_t(settings.width) * size_t(settings.height), glm::vec3(0.0f));
  t->oddSum_ = t->sum_;
  t->passes_ = settings.method == engine::rt::Method::Path ? std::max(1, settings.samplesPerPixel) : 1;
  t->texture_ = engine::gl::Texture::create2D(GL_RGBA8, settings.width, settings.height, 1);
  t->texture_.uploadRgba8(t->pixels_.data());
  t->framebuffer_ = engine::gl::Framebuffer::create();
  t->framebuffer_.attach(GL_COLOR_ATTACHMENT0, t->texture_);
  if (auto s = t->framebuffer_.check("traced image"); !s) return s.error();
  ProgressiveTrace* self = t.get();
  t->worker_ = std::thread([self] { self->traceTiles(); });
  return t;
}

ProgressiveTrace::~ProgressiveTrace() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
}

// One bar over every pass's tiles.
struct ProgressiveTrace::Progress {
  engine::rt::ProgressBar bar;
  std::atomic<int> done{0};
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  std::atomic<std::uint64_t> rays{0};
  std::mutex mutex;
};

void ProgressiveTrace::traceTiles() {
  Progress progress;
  for (int pass = 0; pass < passes_ && !cancel_; ++pass) tracePass(pass, progress);
}

// One pass over the image: the Whitted tracer's whole image, or the path tracer's
// sample `pass` of every pixel.
void ProgressiveTrace::tracePass(int pass, Progress& state) {
  const int perPass = passes_ > 1 ? 1 : std::max(1, settings_.samplesPerPixel);
  tbb::parallel_for(0, tilesX_ * tilesY_, [&](int tile) {
    if (cancel_) return;
    const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
    engine::rt::RayCounters counters;
    const int x1 = std::min(x0 + kTile, settings_.width), y1 = std::min(y0 + kTile, settings_.height);
    glm::vec3 samples[kTile * kTile];
    for (int y = y0; y < y1; ++y) {
      integrator_->renderSpanSamples(x0, x1, y, pass, perPass, &samples[(y - y0) * kTile], &counters);
    }
    // The sums and the bytes change together, under the tile's lock: the noise
    // estimate reads both halves of a pixel at one pass count.
    std::lock_guard<std::mutex> tileLock(tileLocks_[size_t(tile)]);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const std::size_t i = size_t(y) * size_t(settings_.width) + size_t(x);
        const glm::vec3 sample = samples[(y - y0) * kTile + (x - x0)];
        sum_[i] += sample;
        if (pass % 2 == 1) oddSum_[i] += sample;
        const glm::vec3 c = engine::rt::toneMap(sum_[i] / float(pass + 1), scene_->render());
        std::uint8_t* p = &pixels_[i * 4];
        for (int k = 0; k < 3; ++k) p[k] = engine::rt::encodeChannel(c[k], scene_->render().output);
        p[3] = 255;
      }
    }
    tilePasses_[size_t(tile)].store(pass + 1, std::memory_order_release);
    state.rays += counters.total();
    if (!progressBar_) return;
    engine::rt::RenderProgress progress;
    progress.tilesDone = ++state.done;
    progress.tilesTotal = tilesX_ * tilesY_ * passes_;
    progress.rays.primary = state.rays;
    progress.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - state.start).count();
    std::lock_guard<std::mutex> lock(state.mutex);
    state.bar.update(progress);
  });
}

void ProgressiveTrace::uploadFinishedTiles() {
  for (int tile = 0; tile < tilesX_ * tilesY_; ++tile) {
    const int passes = tilePasses_[size_t(tile)].load(std::memory_order_acquire);
    if (tileUploaded_[size_t(tile)] == passes) continue;
    std::lock_guard<std::mutex> lock(tileLocks_[size_t(tile)]);
    const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
    const int w = std::min(kTile, settings_.width - x0), h = std::min(kTile, settings_.height - y0);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, settings_.width);
    glTextureSubImage2D(texture_.id(), 0, x0, y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                        &pixels_[(size_t(y0) * size_t(settings_.width) + size_t(x0)) * 4]);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    tileUploaded_[size_t(tile)] = passes;
  }
}

int ProgressiveTrace::passesDone() const {
  int least = passes_;
  for (int tile = 0; tile < tilesX_ * tilesY_; ++tile)
    least = std::min(least, tilePasses_[size_t(tile)].load(std::memory_order_acquire));
  return least;
}

void ProgressiveTrace::forEachTile(const std::function<void(const TileSpan&)>& visit) const {
  for (int tile = 0; tile < tilesX_ * tilesY_; ++tile) {
    std::lock_guard<std::mutex> lock(tileLocks_[size_t(tile)]);
    const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
    visit({x0, std::min(x0 + kTile, settings_.width), y0, std::min(y0 + kTile, settings_.height),
           tilePasses_[size_t(tile)].load(std::memory_order_acquire)});
  }
}

std::optional<double> ProgressiveTrace::noisePsnr() const {
  if (passesDone() < 2) return std::nullopt;
  const auto& render = scene_->render();
  auto encode = [&render](const glm::vec3& linear, int k) {
    return double(engine::rt::encodeChannel(engine::rt::toneMap(linear, render)[k], render.output));
  };
  double squares = 0.0;
  std::size_t count = 0;
  forEachTile([&](const TileSpan& t) {
    const float odd = float(t.passes / 2), even = float(t.passes - t.passes / 2);
    for (int y = t.y0; y < t.y1; ++y) {
      for (int x = t.x0; x < t.x1; ++x) {
        const std::size_t i = size_t(y) * size_t(settings_.width) + size_t(x);
        const glm::vec3 evenMean = (sum_[i] - oddSum_[i]) / even, oddMean = oddSum_[i] / odd;
        for (int k = 0; k < 3; ++k) {
          const double d = encode(evenMean, k) - encode(oddMean, k);
          squares += d * d;
        }
        count += 3;
      }
    }
  });
  // Each half holds half the samples: twice the variance of the whole, so their
  // difference has four times the whole's mean squared error.
  const double mse = squares / double(std::max<std::size_t>(count, 1)) / 4.0;
  return mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
}

engine::Image ProgressiveTrace::snapshot() const {
  engine::Image image(settings_.width, settings_.height);
  forEachTile([&](const TileSpan& t) {
    for (int y = t.y0; y < t.y1; ++y) {
      const size_t row = size_t(y) * size_t(settings_.width);
      std::copy(&pixels_[(row + size_t(t.x0)) * 4], &pixels_[(row + size_t(t.x1)) * 4], image.at(t.x0, y));
    }
  });
  return image;
}

engine::FloatImage ProgressiveTrace::linearSnapshot() const {
  engine::rt::Framebuffer mean(settings_.width, settings_.height);
  forEachTile([&](const TileSpan& t) {
    if (t.passes == 0) return;  // black, as the encoded image
    for (int y = t.y0; y < t.y1; ++y) {
      for (int x = t.x0; x < t.x1; ++x) mean.at(x, y) = sum_[size_t(y) * size_t(settings_.width) + size_t(x)] / float(t.passes);
    }
  });
  return engine::rt::toFloatImage(mean);
}

}  // namespace demo
