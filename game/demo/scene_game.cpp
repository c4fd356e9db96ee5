#include "scene_game.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "asset/scene_file.h"
#include "scene/scene.h"

namespace demo {

SceneGame::SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options, bool panel)
    : desc_(std::move(scene)), options_(std::move(options)), panel_(panel) {}

SceneGame::~SceneGame() = default;

engine::Status SceneGame::build(std::shared_ptr<engine::Scene> scene, const engine::SceneRenderOptions& options) {
  // A knob over the same scene keeps what the renderer before it uploaded.
  auto renderer = engine::SceneRenderer::create(scene, options, scene == scene_ ? renderer_.get() : nullptr);
  if (!renderer) return renderer.error();
  renderer_ = std::move(renderer).value();
  scene_ = std::move(scene);
  options_ = options;
  return engine::Ok{};
}

engine::Status SceneGame::init() {
  auto scene = engine::Scene::load(desc_);
  if (!scene) return scene.error();
  if (auto s = build(std::move(scene).value(), options_); !s) return s;
  camera_ = renderer_->initialCamera();
  if (!panel_ && startBookmark_ < 0) return engine::Ok{};
  if (auto s = loadBookmarks(); !s) return s;
  if (startBookmark_ >= 0) {
    if (startBookmark_ >= int(bookmarks_.all().size())) {
      return engine::makeError(bookmarks_.file() + ": --bookmark " + std::to_string(startBookmark_) + ": the file has " +
                               std::to_string(bookmarks_.all().size()) + " bookmarks");
    }
    bookmarks_.apply(startBookmark_, camera_);
  }
  return engine::Ok{};
}

engine::Status SceneGame::loadBookmarks() {
  auto loaded = Bookmarks::load(Bookmarks::fileFor(desc_.path));
  if (!loaded) return loaded.error();
  bookmarks_ = std::move(loaded).value();
  return engine::Ok{};
}

engine::Status SceneGame::bookmarkView() {
  bookmarks_.add(camera_);
  return bookmarks_.save();
}

engine::Status SceneGame::deleteBookmark(int index) {
  bookmarks_.erase(index);
  return bookmarks_.save();
}

engine::Status SceneGame::applyOptions(const engine::SceneRenderOptions& options) {
  const engine::Status status = build(scene_, options);
  lastError_ = status ? "" : status.error().message;
  if (status) updated_ = renderer_->update(scene_->time());
  return status;
}

engine::Status SceneGame::switchScene(const std::string& path) {
  auto desc = engine::loadSceneFile(path);
  engine::Status status = engine::Ok{};
  if (!desc) {
    status = desc.error();
  } else if (auto scene = engine::Scene::load(*desc); !scene) {
    status = scene.error();
  } else if (status = build(std::move(scene).value(), options_); status) {
    desc_ = std::move(desc).value();
    camera_ = renderer_->initialCamera();
    updated_ = renderer_->update(time_.taken ? time_.time : 0.0);
    // A malformed bookmarks file leaves the scene loaded, without bookmarks.
    bookmarks_ = Bookmarks{};
    status = loadBookmarks();
  }
  lastError_ = status ? "" : status.error().message;
  return status;
}

// A failed pose ends the run at the next render, which has no frame to show.
void SceneGame::update(double time, double dt) {
  if (!time_.taken) {
    time_.time = time;
  } else if (!time_.paused) {
    time_.time += dt * time_.speed;
  }
  updated_ = renderer_->update(time_.time);
}

engine::Status SceneGame::render(const engine::FrameInfo& frame) {
  if (!updated_) return updated_;
  if (reference_.mode == ReferenceMode::Off) {
    reference_.view.stop();
    return renderer_->render(camera_, frame.width, frame.height);
  }
  return referenceFrame(frame);
}

namespace {
constexpr int kStillFrames = 10;  // frames without camera motion before the reference starts
}

// The reference traces one view at one time: it starts once the camera has held
// still for a few frames with time paused (or nothing in the scene moving), and
// stops when either moves. The raster frame is compared with it whenever a new
// pass of the reference is finished.
engine::Status SceneGame::referenceFrame(const engine::FrameInfo& frame) {
  ReferencePanel& r = reference_;
  const bool still = camera_.position == r.lastPosition && camera_.forward() == r.lastForward;
  r.stillFrames = still ? r.stillFrames + 1 : 0;
  r.lastPosition = camera_.position;
  r.lastForward = camera_.forward();
  const bool frozen = (time_.taken && time_.paused) || !scene_->animated();
  ReferenceRequest request;
  request.camera = desc_.camera;
  request.camera.position = camera_.position;
  request.camera.forward = camera_.forward();
  request.camera.fovyDegrees = camera_.fovyDegrees;
  // A scene where nothing moves looks the same at every time: the trace keeps going.
  request.time = scene_->animated() ? scene_->time() : 0.0;
  request.width = std::max(1, frame.width / r.divisor);
  request.height = std::max(1, frame.height / r.divisor);
  request.settings.method = r.pathTraced ? engine::rt::Method::Path : engine::rt::Method::Whitted;
  request.settings.samplesPerPixel = r.pathTraced ? 4096 : 1;
  request.settings.maxDepth = r.pathTraced ? 16 : 5;
  request.terrainViewportHeight = renderer_->stats().terrainViewportHeight;
  request.terrainErrorOverride = options_.terrainErrorOverride;
  if (!frozen || !still) {
    r.view.stop();
    r.error.reset();
    r.status = !frozen ? "pause time for a reference" : "hold the camera still for a reference";
  } else if (r.stillFrames >= kStillFrames && !(r.view.running() && r.view.request().sameAs(request))) {
    if (auto s = r.view.update(scene_, request); !s) {
      r.status = s.error().message;
    } else {
      r.status.clear();
      r.comparedPasses = -1;
    }
  }
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  if (r.view.running()) {
    r.view.trace()->uploadFinishedTiles();
    if (auto s = compareWithReference(); !s) r.status = s.error().message;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  if (auto s = renderer_->render(camera_, frame.width, frame.height); !s) return s;
  if (r.view.running()) showReference(frame);
  return engine::Ok{};
}

// The raster frame at the reference's size, read back and compared, once per
// finished pass of the reference.
engine::Status SceneGame::compareWithReference() {
  ReferencePanel& r = reference_;
  ProgressiveTrace& trace = *r.view.trace();
  const int passes = trace.passesDone();
  if (passes == 0 || passes == r.comparedPasses) return engine::Ok{};
  if (!r.compareTarget || r.compareTarget->width() != trace.width() || r.compareTarget->height() != trace.height()) {
    auto target = engine::RenderTarget::create(trace.width(), trace.height(), 1);
    if (!target) return target.error();
    r.compareTarget = std::move(target).value();
  }
  r.compareTarget->bind();
  if (auto s = renderer_->render(camera_, trace.width(), trace.height()); !s) return s;
  r.compareTarget->resolve();
  auto error = r.view.compare(r.compareTarget->readPixels());
  if (!error) return error.error();
  r.error = *error;
  r.comparedPasses = passes;
  return engine::Ok{};
}

// The reference's image (or the heatmap) over the frame just drawn: its right
// half, or all of it. Both images are stored top row first: blitted flipped.
void SceneGame::showReference(const engine::FrameInfo& frame) {
  ReferencePanel& r = reference_;
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  const ProgressiveTrace& trace = *r.view.trace();
  engine::gl::Framebuffer heat;
  GLuint source = trace.framebuffer().id();
  if (r.mode == ReferenceMode::Heatmap && r.view.heatmap()) {
    heat = engine::gl::Framebuffer::create();
    heat.attach(GL_COLOR_ATTACHMENT0, r.view.heatmap());
    source = heat.id();
  }
  const int w = trace.width(), h = trace.height();
  if (r.mode == ReferenceMode::Split) {
    glBlitNamedFramebuffer(source, GLuint(target), w / 2, 0, w, h, frame.width / 2, frame.height, frame.width, 0,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
  } else {
    glBlitNamedFramebuffer(source, GLuint(target), 0, 0, w, h, 0, frame.height, frame.width, 0, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
  }
}

// The last frame's counters, its CPU times and each pass's GPU time (timer
// queries: the latest result the GL has, a frame or two old at most).
engine::Game::Counters SceneGame::frameCounters() {
  const engine::SceneStats& s = renderer_->stats();
  Counters counters{{"draw_calls", s.drawCalls},
                    {"program_changes", s.programChanges},
                    {"objects_drawn", s.objectsDrawn},
                    {"objects_culled", s.objectsCulled},
                    {"terrain_triangles", s.terrainTriangles},
                    {"terrain_patches_hidden", s.terrainPatchesHidden},
                    {"vertices_deformed", double(s.verticesDeformed)},
                    {"frame_copies", s.frameCopies},
                    {"sun_static_kept", s.sunStaticKept},
                    {"triangles_all_passes", double(renderer_->lastFrameTriangles())},
                    {"cpu_ms_animation", s.animationMs},
                    {"cpu_ms_cull", s.cullMs},
                    {"cpu_ms_submit", s.submitMs}};
  // GPU culling (render.gpu_culling): what its compute tested and culled in the
  // last frame, and the CPU time of its passes (SceneStats::gpuCullMs says what).
  if (const engine::CullStats c = renderer_->cullStats(); c.enabled) {
    counters.insert(counters.end(), {{"cull_instances_tested", double(c.instancesTested)},
                                     {"cull_instances_frustum", double(c.instancesFrustum)},
                                     {"cull_instances_occluded", double(c.instancesOccluded)},
                                     {"cull_clusters_tested", double(c.clustersTested)},
                                     {"cull_clusters_frustum", double(c.clustersFrustum)},
                                     {"cull_clusters_occluded", double(c.clustersOccluded)},
                                     {"cull_terrain_patches_tested", double(c.patchesTested)},
                                     {"cull_terrain_patches_frustum", double(c.patchesFrustum)},
                                     {"cull_terrain_patches_occluded", double(c.patchesOccluded)},
                                     {"cull_dispatches", double(s.cullDispatches)},
                                     {"cpu_ms_gpu_cull", s.gpuCullMs}});
  }
  for (const engine::PassTime& t : renderer_->passTimes()) counters.emplace_back("gpu_ms_" + t.pass, t.gpuMs);
  return counters;
}

}  // namespace demo

namespace demo {

// Streamed, not concatenated: g++ 12 warns falsely (-Wrestrict) on a long chain of
// std::string additions.
std::string SceneGame::settingName() const {
  const engine::SceneDesc& scene = renderer_->scene();
  const engine::RenderDesc& r = scene.render;
  const engine::SceneRenderOptions& o = options_;
  auto pick = [](int override, int own) { return override > 0 ? override : own; };
  std::ostringstream name;
  name << "msaa" << pick(o.msaaOverride, r.msaa) << " ss" << pick(o.supersampleOverride, r.supersample) << " shadow"
       << pick(o.shadowMapOverride, r.shadowMapSize) << " pcf"
       << pick(o.pcfKernelOverride, r.shadowFilter == engine::ShadowFilter::Hard ? 1 : r.pcfKernel) << " probe"
       << (o.reflectionProbeOverride >= 0 ? o.reflectionProbeOverride : r.reflectionProbe);
  const engine::Shading shading = o.shadingOverride.value_or(r.shading);
  if (o.shadingOverride && *o.shadingOverride != r.shading) name << (shading == engine::Shading::Pbr ? " pbr" : " classic");
  if (shading == engine::Shading::Pbr) {
    name << " " << engine::ambientName(o.ambientOverride.value_or(engine::ambientOf(scene))) << " ibl"
         << pick(o.iblSizeOverride, r.iblSize);
  }
  if (o.exposureOverride > 0.0f && o.exposureOverride != r.exposure) name << " exposure" << o.exposureOverride;
  if (o.toneMapOverride && *o.toneMapOverride != r.toneMap) {
    for (const auto& [n, t] : engine::toneMapNames())
      if (t == *o.toneMapOverride) name << " tonemap-" << n;
  }
  if (o.outputOverride && *o.outputOverride != r.output) {
    for (const auto& [n, c] : engine::outputNames())
      if (c == *o.outputOverride) name << " output-" << n;
  }
  if (scene.terrain.enabled) name << " lod" << (o.terrainErrorOverride > 0.0 ? o.terrainErrorOverride : scene.terrain.errorPixels);
  if (!scene.models.empty()) {
    name << " skinning-" << engine::skinningName(o.skinningOverride.value_or(r.skinning));
    if (o.skinModeOverride) {
      name << (*o.skinModeOverride == engine::SkinMode::DualQuat ? " dqs"
               : *o.skinModeOverride == engine::SkinMode::None   ? " unskinned"
                                                                 : " lbs");
    }
    if (o.rotations == engine::QuatInterpolation::Nlerp) name << " nlerp";
  }
  return name.str();
}

engine::Status SceneGame::addToTable(const std::string& csvPath) {
  const ReferencePanel& r = reference_;
  if (!r.error) return engine::makeError("no reference to measure against yet: hold the camera still with time paused");
  double gpuMs = 0.0;
  for (const auto& p : renderer_->passTimes()) gpuMs += p.gpuMs;
  std::error_code ec;
  const auto folder = std::filesystem::path(csvPath).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  const bool fresh = !std::filesystem::exists(csvPath, ec);
  std::ofstream out(csvPath, std::ios::app);
  if (!out) return engine::makeError(csvPath + ": cannot append to the table");
  if (fresh) out << "scene,family,setting,time_ms,psnr_db,mean_abs,ssim,reference\n";
  const std::string scene = std::filesystem::path(renderer_->scene().path).stem().string();
  const bool path = r.view.request().settings.method == engine::rt::Method::Path;
  out << scene << ",panel," << settingName() << "," << gpuMs << "," << r.error->psnr << "," << r.error->meanAbs << ","
      << r.error->ssim << "," << (path ? "pathtrace " : "raytrace ") << r.error->spp << "spp\n";
  if (!out) return engine::makeError(csvPath + ": cannot append to the table");
  return engine::Ok{};
}

}  // namespace demo
