// SceneRenderer's public face and its frame: the passes in order.
#include "render/scene_renderer_impl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "asset/scene_file.h"
#include "render/pass_state.h"

namespace engine {
namespace {

// View rotation from a forward and an up vector; a left-handed scene (the course's
// room) puts +x on the right when looking along +z, which mirrors GL's convention.
glm::dmat4 viewRotation(const glm::dvec3& forward, const glm::dvec3& upHint, bool leftHanded) {
  const glm::dvec3 f = glm::normalize(forward);
  const glm::dvec3 r = glm::normalize(leftHanded ? glm::cross(upHint, f) : glm::cross(f, upHint));
  const glm::dvec3 u = leftHanded ? glm::cross(f, r) : glm::cross(r, f);
  glm::dmat4 v(1.0);
  for (int i = 0; i < 3; ++i) {
    v[i][0] = r[i];
    v[i][1] = u[i];
    v[i][2] = -f[i];
  }
  return v;
}

}  // namespace

SceneRenderer::SceneRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) { impl_->stats = &stats_; }

SceneRenderer::~SceneRenderer() = default;

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(std::shared_ptr<Scene> source,
                                                             const SceneRenderOptions& options,
                                                             const SceneRenderer* sharing) {
  auto impl = std::make_unique<Impl>();
  impl->scene = source->desc();
  std::unique_ptr<SceneRenderer> renderer(new SceneRenderer(std::move(impl)));
  const std::shared_ptr<GpuScene> shared = sharing ? sharing->impl_->gpu : nullptr;
  if (auto s = renderer->impl_->init(std::move(source), options, shared); !s) return s.error();
  return renderer;
}

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const SceneDesc& scene, const SceneRenderOptions& options) {
  auto source = Scene::load(scene);
  if (!source) return source.error();
  return create(std::move(source).value(), options);
}

const SceneDesc& SceneRenderer::scene() const { return impl_->scene; }

const EnvironmentLighting* SceneRenderer::environmentLighting() const {
  return impl_->sky->environment();
}

std::vector<CharacterInstance*> SceneRenderer::characters() {
  std::vector<CharacterInstance*> out;
  for (auto& c : impl_->gpu->characters()) out.push_back(c.instance.get());
  return out;
}

Status SceneRenderer::update(double time) {
  const auto start = std::chrono::steady_clock::now();
  if (auto s = impl_->gpu->source().update(time, impl_->rotations); !s) return s;
  impl_->gpu->takePoses();
  impl_->animationMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

void SceneRenderer::setPose(int instance, const Pose& pose) {
  impl_->gpu->setPose(instance, pose);
}

Camera SceneRenderer::initialCamera() const {
  Camera camera;
  const CameraDesc& d = impl_->scene.camera;
  camera.position = d.position;
  camera.fovyDegrees = d.fovyDegrees;
  camera.nearPlane = d.nearPlane;
  camera.farPlane = d.farPlane;
  camera.lookAt(d.position + d.forward);
  return camera;
}

std::vector<PassTime> SceneRenderer::passTimes() const {
  impl_->timers.collect();
  return impl_->timers.times();
}

Status SceneRenderer::render(const Camera& camera, int width, int height) {
  stats_ = SceneStats{};
  stats_.animationMs = impl_->animationMs;
  Impl& s = *impl_;
  // The query spans the whole frame, and is ended even when a pass fails.
  if (!s.primitives) s.primitives = gl::Query::create(GL_PRIMITIVES_GENERATED);
  s.primitives.begin();
  Status status = s.renderFrame(camera, width, height);
  s.primitives.end();
  return status;
}

GLenum SceneRenderer::Impl::depthFormat() const {
  const bool stencilled = (terrain && terrain->deferred()) || (surfaces && surfaces->stencil());
  return stencilled ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F;
}

Status SceneRenderer::Impl::renderFrame(const Camera& camera, int width, int height) {
  const bool deferred = (terrain && terrain->deferred()) || surfaces;
  const auto attach = [this](gl::Framebuffer& target, int w, int h) {
    if (surfaces) surfaces->attach(target, w, h);
    if (terrain && terrain->deferred()) terrain->attach(target, w, h);
    return transmission ? transmission->resize(w, h) : Status(Ok{});
  };
  if (auto s = output->begin(width, height, deferred, depthFormat(), attach); !s) return s;
  const glm::dvec3 cameraPosition = camera.position;
  const double aspect = double(width) / double(height);
  const double fovy = glm::radians(camera.fovyDegrees);
  const glm::dmat4 view = viewRotation(camera.forward(), scene.camera.up, scene.camera.leftHanded);
  const glm::dmat4 projection = reverseZProjection(fovy, aspect, camera.nearPlane, camera.farPlane);
  const glm::dmat4 viewProjection = projection * view;
  const int targetHeight = output->height();

  gpu->place(cameraPosition);
  gpu->chooseLevelsOfDetail(cameraPosition, fovy, targetHeight, camera.nearPlane, render.lodPixels);
  if (terrain) terrain->measure(fovy, targetHeight);
  // Bound for the shadow passes too; filled once the sun's matrices exist.
  frame->bind();
  timers.collect();
  if (AtmosphereTables* air = sky->atmosphere()) {
    // Before anything draws the sky or lit surfaces: the probes' views do too.
    const auto update = [&] { return sky->updateAtmosphere(cameraPosition, glm::mat4(viewProjection)); };
    if (auto s = timers.time("aerial-perspective", update); !s) return s;
    air->bindAerialPerspective();
    frame->setSunTransmittance(air->sunTransmittance());
  }
  const bool staticScene = gpu->characters().empty();  // nothing moves
  if (gpu->skinPrograms() && !staticScene) {
    if (auto s = timers.time("skinning", [&] { return gpu->deform(*stats); }); !s) return s;
  }
  if (point && !(point->drawn() && staticScene)) {
    if (auto s = timers.time("shadow-point", [&] { return point->render(cameraPosition); }); !s) return s;
  }
  if (probes && !(probes->drawn() && staticScene)) {
    const auto drawProbes = [&] { return probes->render(cameraPosition, *gpu, sun.get(), *frame, *world); };
    if (auto s = timers.time("reflection-probes", drawProbes); !s) return s;
  }
  if (sun) {
    const double farPlane = scene.camera.farPlane, nearPlane = camera.nearPlane;
    const ShadowSphere nearSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunShadowDistance));
    const ShadowSphere farSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunFarShadowDistance));
    const auto drawMaps = [&] { return sun->render(nearSphere, farSphere, fovy, targetHeight); };
    if (auto s = timers.time("shadow-sun", drawMaps); !s) return s;
  }
  frame->fill(cameraPosition, glm::mat4(viewProjection));

  output->bindCleared(scene.sky.background, scene.camera.leftHanded);
  View mainView;
  mainView.mirrored = scene.camera.leftHanded;
  mainView.main = true;
  mainView.viewProjection = viewProjection;
  frustumPlanes(viewProjection, mainView.planes);
  mainView.fovy = fovy;
  mainView.width = output->width();
  mainView.height = targetHeight;
  if (auto s = timers.time("world", [&] { return world->draw(mainView, -1, true); }); !s) return s;
  const bool post = !output->direct();
  if (post) timers.begin("post");
  output->finish();
  if (post) timers.end();
  applyPassState(kCallerState);
  return Ok{};
}

double SceneRenderer::sunElevationDegrees() const {
  const auto& sun = impl_->frame->lights().sun;
  if (!sun) return std::nan("");
  return glm::degrees(std::asin(std::clamp(glm::normalize(sun->direction).y, -1.0, 1.0)));
}

void SceneRenderer::setSunElevation(double degrees) {
  const auto& sun = impl_->frame->lights().sun;
  if (!sun) return;
  // The azimuth kept; straight up or down has none, and the sun then rises in -z.
  glm::dvec3 across(sun->direction.x, 0.0, sun->direction.z);
  across = glm::length(across) > 1e-9 ? glm::normalize(across) : glm::dvec3(0.0, 0.0, -1.0);
  const double e = glm::radians(degrees);
  const glm::dvec3 direction = across * std::cos(e) + glm::dvec3(0.0, std::sin(e), 0.0);
  impl_->frame->setSunDirection(glm::vec3(direction));
  impl_->sky->setSunDirection(glm::vec3(direction));
  if (impl_->sun) impl_->sun->setDirection(direction);
}

const AtmosphereTables* SceneRenderer::atmosphereTables() const { return impl_->sky->atmosphere(); }

CullStats SceneRenderer::cullStats() const { return impl_->culling ? impl_->culling->counters() : CullStats{}; }

long long SceneRenderer::lastFrameTriangles() const {
  return impl_->primitives ? static_cast<long long>(impl_->primitives.result()) : 0;
}

namespace {
constexpr const char* kDebugViewNames[] = {"none",      "normal",    "uv",       "basecolor", "metallic",
                                           "roughness", "occlusion", "emissive", "alpha"};
}  // namespace

const char* debugViewName(DebugView view) { return kDebugViewNames[int(view)]; }

std::optional<DebugView> parseDebugView(const std::string& name) {
  for (int i = 0; i < int(std::size(kDebugViewNames)); ++i)
    if (name == kDebugViewNames[i]) return DebugView(i);
  return std::nullopt;
}

std::string debugViewList() {
  std::string list;
  for (const char* name : kDebugViewNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

Result<FloatImage> SceneRenderer::readLinear() const { return impl_->output->readLinear(); }

const terrain::LodSelection* SceneRenderer::mainTerrainSelection() const {
  return impl_->terrain ? &impl_->terrain->mainSelection() : nullptr;
}

std::string SceneRenderer::describe() const {
  const Impl& s = *impl_;
  std::ostringstream out;
  out << "passes:";
  const std::string filter = s.pcfRadius ? "pcf " + std::to_string(2 * s.pcfRadius + 1) : "hard";
  if (s.sun) out << " " << s.sun->describe(filter);
  if (s.point) out << " " << s.point->describe(filter);
  if (s.probes) out << " " << s.probes->describe();
  if (const std::string sky = s.sky->describe(); !sky.empty()) out << " " << sky;
  if (s.gpu->skinPrograms()) out << " " << s.gpu->describeSkinCache();
  if (s.render.lodPixels > 0.0) out << " " << s.gpu->describeLevelsOfDetail(s.render.lodPixels);
  if (s.terrain) out << " " << s.terrain->describe();
  out << " opaque";
  if (s.scene.fog.enabled) out << "+fog";
  if (s.surfaces) out << " " << s.surfaces->describe();
  if (s.culling) out << " " << s.culling->describe();
  if (s.transmission) out << " transmission(copy + mips)";
  if (s.gpu->blends()) out << " blend(sorted)";
  out << " " << s.output->describe();
  if (s.debugView != DebugView::None) out << "\ndebug view: " << debugViewName(s.debugView) << " (no exposure, no tone map)";
  out << "\nshading: " << (s.render.shading == Shading::Classic ? "classic" : "pbr");
  if (s.render.shading == Shading::Pbr) out << ", ambient " << ambientName(s.ambient) << s.sky->describeEnvironmentCost();
  const CompiledLights& lights = s.frame->lights();
  const auto count = [&lights](LightType type) {
    return size_t(std::count_if(lights.others.begin(), lights.others.end(),
                                [type](const LightDesc& l) { return l.type == type; }));
  };
  const size_t directional = count(LightType::Sun), spots = count(LightType::Spot);
  out << "; lights compiled in: " << (lights.sun ? "sun + " : "") << lights.others.size() - directional - spots
      << " point";
  if (spots > 0) out << " + " << spots << " spot";
  if (directional > 0) out << " + " << directional << " directional";
  if (lights.dropped > 0) out << " (" << lights.dropped << " not drawn)";
  out << "\nvariants:";
  for (const auto& v : s.draws->variants().built()) out << " " << v.describe();
  if (const SkinPrograms* skinPrograms = s.gpu->skinPrograms()) {
    out << "\nskin-cache variants:";
    for (const auto& v : skinPrograms->built()) out << " " << v.describe();
  }
  out << "\nlast frame: " << stats_.drawCalls << " draw calls, " << stats_.programChanges << " program changes (" << stats_.programsNeeded << " needed), "
      << stats_.objectsDrawn << " objects drawn, " << stats_.objectsCulled << " culled";
  if (s.terrain) {
    out << ", " << stats_.terrainTriangles << " terrain triangles, " << stats_.terrainPatchesHidden
        << " terrain patches hidden by opaque planes";
  }
  out << "\n";
  return out.str();
}

}  // namespace engine
