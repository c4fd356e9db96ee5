#include "gpu_raytrace.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "gputrace/gpu_poses.h"
#include "gputrace/gpu_tracer.h"
#include "platform/gl_context.h"
#include "progressive_trace.h"
#include "raytrace/tone_map.h"

namespace demo {

engine::Result<engine::rt::RaytraceRun> gpuRaytraceScene(const engine::SceneDesc& desc, double time,
                                                         const engine::rt::RenderSettings& settings,
                                                         engine::Backend backend, const std::string& shaderDir) {
  engine::rt::RaytraceRun run;
  auto scene = engine::rt::buildRtScene(desc, time, settings.height, &run.build);
  if (!scene) return scene.error();
  if (const std::string why = engine::gpurt::unsupported(*scene, settings); !why.empty()) {
    return engine::makeError("--device gpu: " + why);
  }
  engine::ContextOptions context;
  context.width = 16;  // the image is a storage buffer, not the context's surface
  context.height = 16;
  auto gl = engine::createContext(backend, context);
  if (!gl) return engine::makeError("--device gpu: " + gl.error().message);
  auto tracer = engine::gpurt::GpuTracer::create(*scene, shaderDir);
  if (!tracer) return tracer.error();
  auto result = tracer->render(settings);
  if (!result) return result.error();
  run.result = std::move(result).value();
  run.image = engine::rt::toImage(run.result.image, scene->render());
  return run;
}

GpuTraceGame::GpuTraceGame(engine::SceneDesc scene, double time, engine::rt::RenderSettings settings,
                           std::string shaderDir, bool animate, bool wholePasses)
    : desc_(std::move(scene)),
      time_(time),
      settings_(std::move(settings)),
      shaderDir_(std::move(shaderDir)),
      animate_(animate),
      wholePasses_(wholePasses) {}

GpuTraceGame::~GpuTraceGame() { shutdown(); }

engine::Status GpuTraceGame::init() {
  auto scene = engine::rt::AnimatedRtScene::create(desc_, time_, settings_.height);
  if (!scene) return scene.error();
  if (const std::string why = engine::gpurt::unsupported(scene->scene(), settings_); !why.empty()) {
    return engine::makeError("--device gpu: " + why);
  }
  scene_ = std::make_unique<engine::rt::AnimatedRtScene>(std::move(scene).value());
  auto tracer = engine::gpurt::GpuTracer::create(scene_->scene(), shaderDir_);
  if (!tracer) return tracer.error();
  tracer_ = std::make_unique<engine::gpurt::GpuTracer>(std::move(tracer).value());
  passes_ = settings_.method == engine::rt::Method::Path ? std::max(1, settings_.samplesPerPixel) : 1;
  if (wholePasses_) bandRows_ = settings_.height;
  if (animate_) {
    auto poses = engine::gpurt::GpuPoses::create(*scene_, *tracer_, shaderDir_);
    if (!poses) return poses.error();
    poses_ = std::make_unique<engine::gpurt::GpuPoses>(std::move(poses).value());
    passes_ = std::numeric_limits<int>::max();  // until the window closes
  }
  sum_.assign(std::size_t(settings_.width) * std::size_t(settings_.height), glm::vec3(0.0f));
  texture_ = engine::gl::Texture::create2D(GL_RGBA8, settings_.width, settings_.height, 1);
  framebuffer_ = engine::gl::Framebuffer::create();
  framebuffer_.attach(GL_COLOR_ATTACHMENT0, texture_);
  return framebuffer_.check("traced image");
}

namespace {

// The GPU time a frame's band aims at: a window that answers 20-30 times a second.
constexpr double kFrameSeconds = 0.04;

// The rows the next band gets: the last band's rate over kFrameSeconds, a multiple of
// the kernels' 8-row groups, growing at most fourfold a frame.
int nextBandRows(int rows, double seconds, int height) {
  const double perRow = std::max(seconds, 1e-6) / double(rows);
  const int wanted = int(kFrameSeconds / perRow) / 8 * 8;
  return std::clamp(wanted, 8, std::max(8, std::min(4 * rows, height)));
}

}  // namespace

// The pass's next band of rows, added to the sums, and the band's mean so far
// encoded into the texture. Animated, a pass starts by posing the scene at `time`.
engine::Status GpuTraceGame::traceBand(double time) {
  if (animate_ && row_ == 0) {
    if (auto s = scene_->setTime(time); !s) return s;
    poses_->update(*scene_, *tracer_);
  }
  const bool summed = this->summed();
  engine::rt::RenderSettings pass = settings_;
  if (summed) {
    pass.firstSample = done_;
    pass.samplesPerPixel = 1;
    pass.totalSamples = settings_.samplesPerPixel;
  }
  const int rows = std::min(bandRows_, settings_.height - row_);
  auto result = tracer_->render(pass, row_, rows);
  if (!result) return result.error();
  // One sample a pass: its mean is its sum. The Whitted pass is the whole image.
  engine::rt::Framebuffer mean(settings_.width, rows);
  const std::size_t first = std::size_t(row_) * std::size_t(settings_.width);
  for (std::size_t i = 0; i < mean.pixels.size(); ++i) {
    glm::vec3& sum = sum_[first + i];
    sum = summed ? sum + result->image.pixels[i] : result->image.pixels[i];
    mean.pixels[i] = summed ? sum / float(done_ + 1) : sum;
  }
  const engine::Image encoded = engine::rt::toImage(mean, scene_->scene().render());
  glTextureSubImage2D(texture_.id(), 0, 0, row_, settings_.width, rows, GL_RGBA, GL_UNSIGNED_BYTE, encoded.pixels.data());
  if (!wholePasses_) bandRows_ = nextBandRows(rows, result->seconds, settings_.height);
  row_ += rows;
  if (row_ < settings_.height) return engine::Ok{};
  row_ = 0;
  ++done_;
  const char* tracer = settings_.method == engine::rt::Method::Path ? "path tracer" : "Whitted tracer";
  if (animate_) {
    std::fprintf(stderr, "\rGPU %s: pass %d at %.3f s (%zu vertices refitted)", tracer, done_, time, poses_->vertices());
    return engine::Ok{};
  }
  std::fprintf(stderr, "\rGPU %s: pass %d of %d", tracer, done_, passes_);
  if (done_ == passes_) std::fputc('\n', stderr);
  return engine::Ok{};
}

engine::Result<engine::FloatImage> GpuTraceGame::linearFrame() {
  engine::rt::Framebuffer mean(settings_.width, settings_.height);
  for (int y = 0; y < settings_.height; ++y) {
    // The rows the pass under way has traced hold one sample more.
    const int samples = summed() ? done_ + (y < row_ ? 1 : 0) : 1;
    if (samples == 0) continue;
    for (int x = 0; x < settings_.width; ++x) {
      const glm::vec3& sum = sum_[std::size_t(y) * std::size_t(settings_.width) + std::size_t(x)];
      mean.at(x, y) = summed() ? sum / float(samples) : sum;
    }
  }
  return engine::rt::toFloatImage(mean);
}

engine::Status GpuTraceGame::render(const engine::FrameInfo& frame) {
  if (done_ < passes_) {
    if (auto s = traceBand(frame.time); !s) return s;
  }
  showTracedImage(framebuffer_, settings_.width, settings_.height, frame);
  return engine::Ok{};
}

void GpuTraceGame::shutdown() {
  if (poses_ && done_ > 0) std::fputc('\n', stderr);
  poses_.reset();
  tracer_.reset();
  framebuffer_ = {};
  texture_ = {};
}

}  // namespace demo
