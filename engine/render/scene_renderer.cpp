#include "render/scene_renderer_impl.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "asset/scene_file.h"
#include "core/srgb_curve.h"
#include "gl/bindings.h"
#include "render/pass_state.h"

namespace engine {
namespace {

// common/output.glsl's targetColor under DIRECT_OUTPUT on the CPU (the direct path's
// clear colour): exposure, the tone map, then the curve.
glm::vec3 displayValue(glm::vec3 c, const RenderDesc& render) {
  c *= render.exposure;
  if (render.toneMap == ToneMap::Aces && render.output != OutputCurve::Gamma22)
    return glm::vec3(acesSrgbByte(c.r), acesSrgbByte(c.g), acesSrgbByte(c.b)) / 255.0f;
  if (render.toneMap == ToneMap::Reinhard) c = c / (1.0f + c);
  if (render.toneMap == ToneMap::Aces) c = acesFit(c);
  c = glm::clamp(c, 0.0f, 1.0f);
  if (render.output == OutputCurve::Gamma22) return glm::pow(c, glm::vec3(1.0f / 2.2f));
  return glm::vec3(srgbByte(c.r), srgbByte(c.g), srgbByte(c.b)) / 255.0f;
}

// The direct path draws into the caller's framebuffer itself, with no target of its
// own and no copy, when that is a single-sample framebuffer object of the frame's
// size with 8-bit normalised colour (RGBA8 or SRGB8_ALPHA8: with GL_FRAMEBUFFER_SRGB
// off both store the shader's bytes as they are) and 32-bit float depth (the
// reverse-Z depth every pass tests against; fixed-point depth would move bytes).
// On llvmpipe the copy was a shader pass over every pixel: about 3 ms at 1280x720.
bool takesDirectFrame(const gl::FramebufferLayout& l, int width, int height) {
  const bool color8 = l.colorType == GL_UNSIGNED_NORMALIZED && l.colorBits[0] == 8 && l.colorBits[1] == 8 &&
                      l.colorBits[2] == 8 && l.colorBits[3] == 8;
  return l.samples == 0 && l.width == width && l.height == height && color8 && l.depthBits == 32 &&
         l.depthType == GL_FLOAT;
}

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
                                                             const SceneRenderOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->scene = source->desc();
  impl->scene.lights = source->lights();  // the glTF lights of its models too
  std::unique_ptr<SceneRenderer> renderer(new SceneRenderer(std::move(impl)));
  if (auto s = renderer->impl_->init(std::move(source), options); !s) return s.error();
  return renderer;
}

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const SceneDesc& scene, const SceneRenderOptions& options) {
  auto source = Scene::load(scene);
  if (!source) return source.error();
  return create(std::move(source).value(), options);
}

const SceneDesc& SceneRenderer::scene() const { return impl_->scene; }

const EnvironmentLighting* SceneRenderer::environmentLighting() const {
  return impl_->environmentLighting ? &*impl_->environmentLighting : nullptr;
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

void SceneRenderer::Impl::beginTimer(const std::string& pass) {
  auto it = std::find_if(timers.begin(), timers.end(), [&](const PassTimer& t) { return t.pass == pass; });
  if (it == timers.end()) it = timers.insert(timers.end(), PassTimer{pass, gl::Query::create(GL_TIME_ELAPSED)});
  activeTimer = it->pending ? -1 : int(it - timers.begin());
  if (activeTimer >= 0) it->query.begin();
}

void SceneRenderer::Impl::endTimer() {
  if (activeTimer < 0) return;
  timers[size_t(activeTimer)].query.end();
  timers[size_t(activeTimer)].pending = true;
  activeTimer = -1;
}

void SceneRenderer::Impl::collectTimers() {
  for (PassTimer& t : timers) {
    if (!t.pending || !t.query.available()) continue;
    t.ms = double(t.query.result()) * 1e-6;
    t.pending = false;
  }
}

std::vector<PassTime> SceneRenderer::passTimes() const {
  impl_->collectTimers();
  std::vector<PassTime> out;
  for (const auto& t : impl_->timers) out.push_back({t.pass, t.ms});
  return out;
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
  s.primitivesValid = true;
  return status;
}

// The direct path's colour image in drawFbo: the caller's (`caller`, when it can be
// attached elsewhere), else drawFbo's own. True when the caller's is attached.
// Attached anew every frame: a caller's resized target may be a new image under
// the name of the one it deleted.
bool SceneRenderer::Impl::useColourOf(const gl::FramebufferLayout* caller) {
  const GLuint wanted = caller && caller->colorObjectType != GL_NONE ? caller->colorObject : 0;
  if (wanted == 0) {
    if (borrowedColour != 0) drawFbo.attach(GL_COLOR_ATTACHMENT0, hdr);
  } else if (caller->colorObjectType == GL_RENDERBUFFER) {
    glNamedFramebufferRenderbuffer(drawFbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, wanted);
  } else {
    glNamedFramebufferTexture(drawFbo.id(), GL_COLOR_ATTACHMENT0, wanted, caller->colorLevel);
  }
  borrowedColour = wanted;
  return wanted != 0;
}

Status SceneRenderer::Impl::renderFrame(const Camera& camera, int width, int height) {
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  const gl::FramebufferLayout callerLayout = gl::framebufferLayout(GLuint(callerFramebuffer));
  const bool direct = directOutput && takesDirectFrame(callerLayout, width, height);
  // Deferred surfaces need their targets (and stencil) beside the frame's depth:
  // drawFbo then borrows the caller's colour image where it can, so nothing is copied.
  const bool intoCaller = direct && !(terrain && terrain->deferred()) && !surfaces;
  if (intoCaller) {
    targetWidth = width;
    targetHeight = height;
  } else if (auto status = makeTarget(width, height); !status) {
    return status;
  }
  const bool borrowed = directOutput && !intoCaller && useColourOf(direct ? &callerLayout : nullptr);
  if (displayTable) displayTable.bind(gl::binding::kDisplayTable);
  const glm::dvec3 cameraPosition = camera.position;
  const double aspect = double(width) / double(height);
  const double fovy = glm::radians(camera.fovyDegrees);
  const glm::dmat4 view = viewRotation(camera.forward(), scene.camera.up, scene.camera.leftHanded);
  const glm::dmat4 projection = reverseZProjection(fovy, aspect, camera.nearPlane, camera.farPlane);
  const glm::dmat4 viewProjection = projection * view;
  glm::dvec4 planes[6];
  frustumPlanes(viewProjection, planes);

  gpu->place(cameraPosition);
  gpu->chooseLevelsOfDetail(cameraPosition, fovy, targetHeight, camera.nearPlane, render.lodPixels);
  if (terrain) terrain->measure(fovy, targetHeight);
  // Bound before the shadow passes; filled once the sun's matrices exist.
  frame->bind();
  collectTimers();
  const bool staticScene = gpu->characters().empty();  // nothing moves
  if (gpu->skinPrograms() && !staticScene) {
    beginTimer("skinning");
    const Status status = gpu->deform(*stats);
    endTimer();
    if (!status) return status;
  }
  if (point && !(point->drawn() && staticScene)) {
    beginTimer("shadow-point");
    const Status status = point->render(cameraPosition);
    endTimer();
    if (!status) return status;
  }
  if (probes && !(probes->drawn() && staticScene)) {
    beginTimer("reflection-probes");
    const Status status = probes->render(cameraPosition, *gpu, sun.get(), *frame, [this](const View& face, int mirror) {
      return drawWorld(face, mirror, false);
    });
    endTimer();
    if (!status) return status;
  }
  if (sun) {
    const double farPlane = scene.camera.farPlane, nearPlane = camera.nearPlane;
    const ShadowSphere nearSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunShadowDistance));
    const ShadowSphere farSphere =
        frustumSlice(view, fovy, aspect, nearPlane, std::min(farPlane, kSunFarShadowDistance));
    beginTimer("shadow-sun");
    const Status status = sun->render(nearSphere, farSphere, fovy, targetHeight);
    endTimer();
    if (!status) return status;
  }
  frame->fill(cameraPosition, glm::mat4(viewProjection));

  glBindFramebuffer(GL_FRAMEBUFFER, intoCaller ? GLuint(callerFramebuffer) : drawFbo.id());
  glViewport(0, 0, targetWidth, targetHeight);
  glDisable(GL_FRAMEBUFFER_SRGB);
  applyPassState(opaquePassFor(scene.camera.leftHanded));  // depth writes on, for the clear
  const glm::vec3 background = directOutput ? displayValue(scene.sky.background, render) : scene.sky.background;
  glClearColor(background.r, background.g, background.b, 1.0f);
  glClearDepth(0.0);  // reverse-Z: far is 0
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  View mainView;
  mainView.mirrored = scene.camera.leftHanded;
  mainView.main = true;
  mainView.viewProjection = viewProjection;
  std::copy(std::begin(planes), std::end(planes), std::begin(mainView.planes));
  mainView.fovy = fovy;
  mainView.width = targetWidth;
  mainView.height = targetHeight;
  beginTimer("world");
  const Status world = drawWorld(mainView, -1, true);
  endTimer();
  if (!world) return world;
  if (directOutput) {
    // Display values already: drawn into the caller's framebuffer, or copied into it
    // as they are.
    glClearDepth(1.0);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
    glViewport(0, 0, width, height);
    if (!intoCaller && !borrowed) {
      stats->frameCopies = 1;
      glBlitNamedFramebuffer(drawFbo.id(), GLuint(callerFramebuffer), 0, 0, targetWidth, targetHeight, 0, 0, width,
                             height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    applyPassState(kCallerState);
    return Ok{};
  }
  beginTimer("post");

  if (render.msaa > 1) {
    glBlitNamedFramebuffer(drawFbo.id(), resolveFbo.id(), 0, 0, targetWidth, targetHeight, 0, 0,
                           targetWidth, targetHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  // Post: into the framebuffer the caller bound. It receives display values, so
  // sRGB encoding on write is off (the shader applies the output curve itself).
  applyPassState(kPostPass);
  stats->frameCopies = 1;
  glClearDepth(1.0);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  glViewport(0, 0, width, height);
  glDisable(GL_FRAMEBUFFER_SRGB);
  post.use();
  post.set("u_exposure", render.exposure);
  hdr.bind(gl::binding::kHdr);
  emptyVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  endTimer();
  applyPassState(kCallerState);
  stats->drawCalls += 1;
  return Ok{};
}

CullStats SceneRenderer::cullStats() const {
  CullStats out;
  if (!impl_->culler) return out;
  const cull::Counters c = impl_->culler->counters();
  out.enabled = true;
  out.instancesTested = c.instancesTested;
  out.instancesFrustum = c.instancesFrustum;
  out.instancesOccluded = c.instancesOccluded;
  out.clustersTested = c.clustersTested;
  out.clustersFrustum = c.clustersFrustum;
  out.clustersOccluded = c.clustersOccluded;
  if (impl_->terrainCuller) {
    const cull::Counters t = impl_->terrainCuller->counters();
    out.patchesTested = t.clustersTested;
    out.patchesFrustum = t.clustersFrustum;
    out.patchesOccluded = t.clustersOccluded;
  }
  return out;
}

long long SceneRenderer::lastFrameTriangles() const {
  return impl_->primitivesValid ? static_cast<long long>(impl_->primitives.result()) : 0;
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
  if (s.scene.sky.enabled) out << " sky";
  if (const gl::Texture& image = s.gpu->skyImage()) {
    out << "(image " << std::filesystem::path(s.scene.sky.image).filename().string() << " " << image.width() << "x"
        << image.height() << ")";
  }
  if (s.environmentLighting) out << " " << ambientName(s.ambient) << "(" << s.environmentLighting->describe() << ")";
  if (s.gpu->skinPrograms()) out << " " << s.gpu->describeSkinCache();
  if (s.render.lodPixels > 0.0) out << " " << s.gpu->describeLevelsOfDetail(s.render.lodPixels);
  if (s.terrain) out << " " << s.terrain->describe();
  out << " opaque";
  if (s.scene.fog.enabled) out << "+fog";
  if (s.surfaces) out << " " << s.surfaces->describe();
  if (s.culler) {
    out << " gpu-culling(" << s.culler->clusters().size() << " clusters of <= " << cull::kClusterTriangles
        << " triangles; " << (s.render.msaa > 1 ? "frustum only (msaa)" : "frustum + hi-z, occluder prepass")
        << (s.terrainCuller ? "; terrain patches too" : "") << ")";
  }
  if (s.gpu->refracts()) out << " transmission(copy + mips)";
  if (s.gpu->blends()) out << " blend(sorted)";
  if (s.directOutput) {
    out << " direct(display values from the fragment shaders: exposure, tone map and curve applied there; RGBA8, no"
           " post pass; into the caller's framebuffer when it is single-sample RGBA8 with float depth (its colour image"
           " with the deferred surfaces' depth-stencil and targets), else copied)";
  } else {
    out << " post(msaa " << s.render.msaa << ", supersample " << s.render.supersample << ")";
  }
  if (s.debugView != DebugView::None) out << "\ndebug view: " << debugViewName(s.debugView) << " (no exposure, no tone map)";
  out << "\nshading: " << (s.render.shading == Shading::Classic ? "classic" : "pbr");
  if (s.render.shading == Shading::Pbr) {
    out << ", ambient " << ambientName(s.ambient);
    if (s.environmentLighting) out << " (built once in " << std::fixed << std::setprecision(1) << s.iblMilliseconds << " ms)";
  }
  out << "; lights compiled in: " << (s.lights.sun >= 0 ? "sun + " : "") << s.lights.points.size() << " point";
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
