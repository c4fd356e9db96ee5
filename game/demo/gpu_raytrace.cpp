#include "gpu_raytrace.h"

#include <cstdio>

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
                           std::string shaderDir)
    : desc_(std::move(scene)), time_(time), settings_(std::move(settings)), shaderDir_(std::move(shaderDir)) {}

GpuTraceGame::~GpuTraceGame() { shutdown(); }

engine::Status GpuTraceGame::init() {
  auto scene = engine::rt::buildRtScene(desc_, time_, settings_.height);
  if (!scene) return scene.error();
  if (const std::string why = engine::gpurt::unsupported(*scene, settings_); !why.empty()) {
    return engine::makeError("--device gpu: " + why);
  }
  scene_ = std::make_unique<engine::rt::RtScene>(std::move(scene).value());
  auto tracer = engine::gpurt::GpuTracer::create(*scene_, shaderDir_);
  if (!tracer) return tracer.error();
  tracer_ = std::make_unique<engine::gpurt::GpuTracer>(std::move(tracer).value());
  passes_ = settings_.method == engine::rt::Method::Path ? std::max(1, settings_.samplesPerPixel) : 1;
  sum_.assign(std::size_t(settings_.width) * std::size_t(settings_.height), glm::vec3(0.0f));
  texture_ = engine::gl::Texture::create2D(GL_RGBA8, settings_.width, settings_.height, 1);
  framebuffer_ = engine::gl::Framebuffer::create();
  framebuffer_.attach(GL_COLOR_ATTACHMENT0, texture_);
  return framebuffer_.check("traced image");
}

// The next pass, added to the sums, and the mean so far encoded into the texture.
engine::Status GpuTraceGame::tracePass() {
  engine::rt::RenderSettings pass = settings_;
  if (passes_ > 1) {
    pass.firstSample = done_;
    pass.samplesPerPixel = 1;
    pass.totalSamples = settings_.samplesPerPixel;
  }
  auto result = tracer_->render(pass);
  if (!result) return result.error();
  ++done_;
  // One sample a pass: its mean is its sum. The Whitted pass is the whole image.
  engine::rt::Framebuffer mean(settings_.width, settings_.height);
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    sum_[i] = passes_ > 1 ? sum_[i] + result->image.pixels[i] : result->image.pixels[i];
    mean.pixels[i] = passes_ > 1 ? sum_[i] / float(done_) : sum_[i];
  }
  texture_.uploadRgba8(engine::rt::toImage(mean, scene_->render()).pixels.data());
  std::fprintf(stderr, "\rGPU %s: pass %d of %d", passes_ > 1 ? "path tracer" : "Whitted tracer", done_, passes_);
  if (done_ == passes_) std::fputc('\n', stderr);
  return engine::Ok{};
}

engine::Status GpuTraceGame::render(const engine::FrameInfo& frame) {
  if (done_ < passes_) {
    if (auto s = tracePass(); !s) return s;
  }
  showTracedImage(framebuffer_, settings_.width, settings_.height, frame);
  return engine::Ok{};
}

void GpuTraceGame::shutdown() {
  tracer_.reset();
  framebuffer_ = {};
  texture_ = {};
}

}  // namespace demo
