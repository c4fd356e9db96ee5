#include "reference_view.h"

#include "raytrace/scene_builder.h"
#include "scene/scene.h"

namespace demo {

bool ReferenceRequest::sameAs(const ReferenceRequest& o) const {
  const auto& a = camera;
  const auto& b = o.camera;
  return a.position == b.position && a.forward == b.forward && a.fovyDegrees == b.fovyDegrees && time == o.time &&
         width == o.width && height == o.height && settings.method == o.settings.method &&
         settings.samplesPerPixel == o.settings.samplesPerPixel && settings.maxDepth == o.settings.maxDepth &&
         settings.seed == o.settings.seed && terrainViewportHeight == o.terrainViewportHeight &&
         terrainErrorOverride == o.terrainErrorOverride;
}

// The tracer's scene is built here, on the caller's thread, while nothing poses
// the shared scene; the worker then traces its own copy and never touches it.
engine::Status ReferenceView::update(std::shared_ptr<engine::Scene> scene, const ReferenceRequest& request) {
  if (trace_ && request.sameAs(request_)) return engine::Ok{};
  trace_.reset();
  if (auto s = scene->update(request.time); !s) return s;
  const int lodHeight = request.terrainViewportHeight > 0 ? request.terrainViewportHeight : request.height;
  auto built = engine::rt::AnimatedRtScene::create(std::move(scene), lodHeight, nullptr, &request.camera,
                                                   request.terrainErrorOverride);
  if (!built) return built.error();
  engine::rt::RenderSettings settings = request.settings;
  settings.width = request.width;
  settings.height = request.height;
  auto trace = ProgressiveTrace::start(std::make_unique<engine::rt::RtScene>(std::move(built->scene())), settings, false);
  if (!trace) return trace.error();
  trace_ = std::move(trace).value();
  request_ = request;
  return engine::Ok{};
}

engine::Result<ReferenceError> ReferenceView::compare(const engine::Image& raster) {
  if (!trace_) return engine::makeError("no reference is being traced");
  const engine::Image reference = trace_->snapshot();
  auto diff = engine::compareImages(raster, reference);
  if (!diff) return diff.error();
  auto ssim = engine::structuralSimilarity(raster, reference);
  if (!ssim) return ssim.error();
  engine::Image heat = engine::diffImage(raster, reference);
  if (!heatmap_ || heatmap_.width() != heat.width || heatmap_.height() != heat.height)
    heatmap_ = engine::gl::Texture::create2D(GL_RGBA8, heat.width, heat.height, 1);
  heatmap_.uploadRgba8(heat.pixels.data());
  const int done = trace_->passesDone();
  const int spp = request_.settings.method == engine::rt::Method::Path ? done : request_.settings.samplesPerPixel;
  return ReferenceError{spp, diff->psnr, diff->meanAbs, *ssim, trace_->noisePsnr()};
}

}  // namespace demo
