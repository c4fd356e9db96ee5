#include "raytrace_game.h"

#include <tbb/parallel_for.h>

#include "raytrace/progress_bar.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"

namespace demo {
namespace {
constexpr int kTile = 16;
}

RaytraceGame::RaytraceGame(engine::SceneDesc scene, double time, engine::rt::RenderSettings settings)
    : desc_(std::move(scene)), time_(time), settings_(std::move(settings)) {}

RaytraceGame::~RaytraceGame() { shutdown(); }

engine::Status RaytraceGame::init() {
  auto scene = engine::rt::buildRtScene(desc_, time_, settings_.height);
  if (!scene) return scene.error();
  scene_ = std::make_unique<engine::rt::RtScene>(std::move(scene).value());
  integrator_ = std::make_unique<engine::rt::Integrator>(*scene_, settings_);
  tilesX_ = (settings_.width + kTile - 1) / kTile;
  tilesY_ = (settings_.height + kTile - 1) / kTile;
  tilePasses_ = std::make_unique<std::atomic<int>[]>(size_t(tilesX_ * tilesY_));
  tileUploaded_.assign(size_t(tilesX_ * tilesY_), 0);
  tileLocks_ = std::make_unique<std::mutex[]>(size_t(tilesX_ * tilesY_));
  pixels_.assign(size_t(settings_.width) * size_t(settings_.height) * 4, 0);
  sum_.assign(size_t(settings_.width) * size_t(settings_.height), glm::vec3(0.0f));
  passes_ = settings_.method == engine::rt::Method::Path ? std::max(1, settings_.samplesPerPixel) : 1;
  texture_ = engine::gl::Texture::create2D(GL_RGBA8, settings_.width, settings_.height, 1);
  texture_.uploadRgba8(pixels_.data());
  source_ = engine::gl::Framebuffer::create();
  source_.attach(GL_COLOR_ATTACHMENT0, texture_);
  if (auto s = source_.check("ray-traced image"); !s) return s;
  worker_ = std::thread([this] { traceTiles(); });
  return engine::Ok{};
}

// One bar over every pass's tiles.
struct RaytraceGame::Progress {
  engine::rt::ProgressBar bar;
  std::atomic<int> done{0};
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  std::atomic<std::uint64_t> rays{0};
  std::mutex mutex;
};

void RaytraceGame::traceTiles() {
  Progress progress;
  for (int pass = 0; pass < passes_ && !cancel_; ++pass) tracePass(pass, progress);
}

// One pass over the image: the Whitted tracer's whole image, or the path tracer's
// sample `pass` of every pixel. renderPixelSamples gives each pixel exactly what
// render() would (the same RNG streams), so the window converges to the image the
// offscreen mode writes.
void RaytraceGame::tracePass(int pass, Progress& state) {
  const int perPass = passes_ > 1 ? 1 : std::max(1, settings_.samplesPerPixel);
  tbb::parallel_for(0, tilesX_ * tilesY_, [&](int tile) {
    if (cancel_) return;
    const int x0 = (tile % tilesX_) * kTile, y0 = (tile / tilesX_) * kTile;
    engine::rt::RayCounters counters;
    const int x1 = std::min(x0 + kTile, settings_.width), y1 = std::min(y0 + kTile, settings_.height);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        sum_[size_t(y) * size_t(settings_.width) + size_t(x)] += integrator_->renderPixelSamples(x, y, pass, perPass, &counters);
      }
    }
    std::lock_guard<std::mutex> tileLock(tileLocks_[size_t(tile)]);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const std::size_t i = size_t(y) * size_t(settings_.width) + size_t(x);
        const glm::vec3 c = engine::rt::toneMap(sum_[i] / float(pass + 1), scene_->render());
        std::uint8_t* p = &pixels_[i * 4];
        for (int k = 0; k < 3; ++k) p[k] = engine::rt::encodeChannel(c[k], scene_->render().output);
        p[3] = 255;
      }
    }
    tilePasses_[size_t(tile)].store(pass + 1, std::memory_order_release);
    state.rays += counters.total();
    engine::rt::RenderProgress progress;
    progress.tilesDone = ++state.done;
    progress.tilesTotal = tilesX_ * tilesY_ * passes_;
    progress.rays.primary = state.rays;
    progress.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - state.start).count();
    std::lock_guard<std::mutex> lock(state.mutex);
    state.bar.update(progress);
  });
}

void RaytraceGame::uploadFinishedTiles() {
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

engine::Status RaytraceGame::render(const engine::FrameInfo& frame) {
  uploadFinishedTiles();
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  // The texture holds encoded display values: copy them as they are, flipped (the
  // image's first row is the top one).
  glDisable(GL_FRAMEBUFFER_SRGB);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBlitNamedFramebuffer(source_.id(), GLuint(target), 0, 0, settings_.width, settings_.height, 0, frame.height,
                         frame.width, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return engine::Ok{};
}

void RaytraceGame::shutdown() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
  texture_.reset();
  source_.reset();
}

}  // namespace demo
