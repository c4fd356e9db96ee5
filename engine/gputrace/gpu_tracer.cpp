#include "gputrace/gpu_tracer.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <optional>

#include "core/sheen_table.h"
#include "gl/bindings.h"
#include "gputrace/gpu_materials.h"
#include "gputrace/gpu_tracer_impl.h"
#include "gputrace/gpu_textures.h"
#include "raytrace/ray_cone.h"
#include "raytrace/tile_render.h"
#include "scene/environment.h"

namespace engine::gpurt {
namespace {

std::string floatDefine(const char* name, float value) {
  char text[96];
  std::snprintf(text, sizeof(text), "%s uintBitsToFloat(0x%08xu)", name, std::bit_cast<std::uint32_t>(value));
  return text;
}

// std430 twin of whitted.comp's RtLight.
struct GpuLight {
  glm::ivec4 typeShadowsFalloff;
  glm::vec4 position, direction, radiance, edgeU, edgeV;
  glm::vec4 cone;  // the cone's axis toward the light; w: the outer cosine, and position.w the inner
};

std::vector<GpuLight> lightsOf(const rt::RtScene& scene) {
  std::vector<GpuLight> out;
  for (const LightDesc& l : scene.lights()) {
    const int type = l.type == LightType::Sun ? 0 : l.type == LightType::Area ? 2 : 1;
    const LightCone cone = lightCone(l);
    out.push_back(GpuLight{glm::ivec4(type, l.shadows ? 1 : 0, l.falloff ? 1 : 0, 0),
                           glm::vec4(glm::vec3(l.position), cone.cosInner), glm::vec4(glm::vec3(l.direction), 0.0f),
                           glm::vec4(l.color * l.intensity, 0.0f), glm::vec4(glm::vec3(l.edgeU), 0.0f),
                           glm::vec4(glm::vec3(l.edgeV), 0.0f), glm::vec4(cone.axisToLight, cone.cosOuter)});
  }
  return out;
}

// Whether each array fits the largest storage block the GL allows (llvmpipe: 128 MiB;
// an 8192 x 4096 sky is 384 MiB): an error naming the first that does not.
Status fitsStorageBlocks(std::initializer_list<std::pair<const char*, std::size_t>> arrays) {
  GLint64 largest = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
  for (const auto& [what, bytes] : arrays) {
    if (GLint64(bytes) > largest) {
      return makeError(std::string(what) + " take " + std::to_string(bytes >> 20) + " MiB, more than the GL's largest storage block (" +
                       std::to_string(largest >> 20) + " MiB)");
    }
  }
  return Ok{};
}

}  // namespace

namespace detail {

bool hasSheen(const rt::RtScene& scene) {
  const auto& materials = scene.materials();
  return std::any_of(materials.begin(), materials.end(), [](const MaterialDesc& m) { return m.layers.sheen(); });
}

std::vector<std::string> traceDefines(const rt::GpuSceneLayout& layout, const rt::RtScene* shaded) {
  std::vector<std::string> defines{"RT_WIDTH " + std::to_string(layout.width), "RT_STACK_SIZE " + std::to_string(layout.stackSize()),
          floatDefine("RT_GAMMA2", rt::gamma<float>(2)),
          floatDefine("RT_GAMMA3", rt::gamma<float>(3)),
          floatDefine("RT_GAMMA5", rt::gamma<float>(5)),
          floatDefine("RT_GAMMA7", rt::gamma<float>(7)),
          floatDefine("RT_GAMMA8", rt::gamma<float>(8)),
          floatDefine("RT_WIDEN", 1.0f + 2.0f * rt::gamma<float>(3))};
  if (!shaded) return defines;
  if (shaded->hasTextures()) defines.emplace_back("RT_TEXTURES 1");
  if (layout.hasUvs) defines.emplace_back("RT_TRIANGLE_UVS 1");
  if (layout.hasColors) defines.emplace_back("RT_TRIANGLE_COLORS 1");
  defines.push_back("RT_ATTRIBUTE_SLOTS " + std::to_string(layout.attributeSlots()));
  if (shaded->environment().hasImage()) defines.emplace_back("RT_SKY_IMAGE 1");
  if (shaded->hasTransparency() || shaded->hasSingleSided()) defines.emplace_back("RT_PASS_THROUGH 1");
  if (shaded->hasTransparency()) defines.emplace_back("RT_TRANSPARENT 1");
  if (hasSheen(*shaded)) defines.emplace_back("RT_SHEEN_TABLE 1");
  return defines;
}

}  // namespace detail

std::string unsupported(const rt::RtScene& scene, const rt::RenderSettings& settings) {
  if (settings.precision != rt::Precision::Float) return "double precision is not supported";
  if (!rt::fitsGpuTextures(scene)) return "textures of more than 32768 texels a side are not supported";
  if (settings.method == rt::Method::Path && scene.fog().enabled && scene.fog().model == FogModel::Volumetric)
    return "a volumetric fog is not supported (the CPU path tracer renders it)";
  if (settings.method == rt::Method::Path && (scene.atmosphere().enabled || !scene.media().empty()))
    return "an atmosphere and boxes of fog are not supported (the CPU path tracer renders them)";
  // Both integrators draw every layer glTF has, with its textures.
  return {};
}

std::string describe(const rt::RtScene& scene, const rt::RenderSettings& settings) {
  const rt::GpuSceneLayout layout = rt::flattenScene(scene, 4);
  const rt::GpuTextureSet textures = rt::flattenTextures(scene);
  const bool path = settings.method == rt::Method::Path;
  std::string out = path ? "gpu kernel: rt/pathtrace.comp" : "gpu kernel: rt/whitted.comp";
  // The variant: what the scene needs built in (the error bounds' constants aside).
  for (const std::string& define : detail::traceDefines(layout, &scene)) {
    if (define.starts_with("RT_GAMMA") || define.starts_with("RT_WIDEN")) continue;
    out.push_back(' ');
    out.append(define);
    out[out.rfind(' ')] = '=';
  }
  if (!path) out.append(" RT_MAX_DEPTH=").append(std::to_string(std::max(0, settings.maxDepth)));
  char line[128];
  std::snprintf(line, sizeof(line), "\ngpu bvh: 4 wide, %d levels, %zu instances\ngpu buffers:", layout.depth,
                layout.instances.size());
  out.append(line);
  const FloatImage* sky = scene.environment().image();
  const std::pair<const char*, std::size_t> buffers[] = {
      {"nodes", layout.nodes4.size() * sizeof(rt::GpuNode4)},
      {"leaves", layout.leaves.size() * sizeof(rt::GpuLeaf)},
      {"triangles", layout.triangles.size() * sizeof(rt::GpuTriangle)},
      {"triangle attributes", layout.triangleAttributes.size() * sizeof(glm::vec4)},
      {"spheres", layout.spheres.size() * sizeof(rt::GpuSphere)},
      {"planes", layout.planes.size() * sizeof(rt::GpuPlane)},
      {"materials", scene.materials().size() * sizeof(GpuMaterial)},
      {"textures", textures.texels.size() * sizeof(glm::vec4)},
      {"sky image", sky ? sky->rgb.size() * sizeof(float) : 0}};
  for (const auto& [name, bytes] : buffers) {
    if (bytes == 0) continue;
    if (bytes >= (1u << 20)) {
      std::snprintf(line, sizeof(line), " %s %.1f MiB,", name, double(bytes) / double(1 << 20));
    } else {
      std::snprintf(line, sizeof(line), " %s %.1f KiB,", name, double(bytes) / 1024.0);
    }
    out.append(line);
  }
  out.back() = '\n';
  return out;
}

void GpuTracer::State::bindScene(const gl::Program& program) const {
  const std::pair<unsigned, const gl::Buffer*> buffers[] = {
      {gl::binding::kRtNodes, &nodes},         {gl::binding::kRtLeaves, &leaves},
      {gl::binding::kRtOrder, &order},         {gl::binding::kRtInstances, &instances},
      {gl::binding::kRtSpheres, &spheres},     {gl::binding::kRtPlanes, &planes},
      {gl::binding::kRtTriangles, &triangles}, {gl::binding::kRtMaterials, &materials},
      {gl::binding::kRtLights, &lights},       {gl::binding::kRtTriangleAttributes, &triangleAttributes},
      {gl::binding::kRtTextures, &textures},   {gl::binding::kRtTexels, &texels},
      {gl::binding::kRtSkyImage, &skyImage}};
  for (const auto& [unit, buffer] : buffers) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, unit, buffer->id());
  program.use();
  program.set("u_instanceCount", int(layout.instances.size()));
  program.set("u_sphereCount", int(layout.spheres.size()));
  program.set("u_planeCount", int(layout.planes.size()));
}

void GpuTracer::State::setView(const gl::Program& p, const rt::RenderSettings& settings) const {
  const int w = settings.width, h = settings.height;
  const CameraDesc& camera = scene->camera();
  // PinholeCamera's basis and scales, in double.
  const glm::dvec3 forward = glm::normalize(camera.forward);
  const glm::dvec3 up = glm::normalize(camera.up - glm::dot(camera.up, forward) * forward);
  const double yScale = std::tan(glm::radians(camera.fovyDegrees) * 0.5);
  const auto set3d = [&](const char* name, const glm::dvec3& v) { glUniform3d(p.location(name), v.x, v.y, v.z); };
  set3d("u_cameraPosition", camera.position);
  set3d("u_cameraRight", camera.right());
  set3d("u_cameraUp", up);
  set3d("u_cameraForward", forward);
  glUniform2d(p.location("u_cameraScale"), yScale * double(w) / double(h), yScale);
  glUniform1d(p.location("u_farPlane"), camera.farPlane);
  glUniform2i(p.location("u_size"), w, h);
  glUniform2ui(p.location("u_seed"), GLuint(settings.seed & 0xffffffffu), GLuint(settings.seed >> 32));
  const SkyDesc& sky = scene->sky();
  const rt::Environment& environment = scene->environment();
  p.set("u_skyKind", environment.isConstant() ? 0 : environment.hasImage() ? 2 : 1);
  if (const FloatImage* image = environment.image()) {  // RT_SKY_IMAGE's
    glUniform2i(p.location("u_skyImageSize"), image->width, image->height);
    p.set("u_skyIntensity", environment.intensity());
    p.set("u_skyRotation", environment.rotation());
  }
  p.set("u_background", sky.background);
  p.set("u_zenith", sky.zenith);
  p.set("u_horizon", sky.horizon);
  p.set("u_ground", sky.ground);
  // The gradient's disk is toward the last sun light (RtScene::sunDirection).
  std::optional<glm::vec3> sun;
  for (const LightDesc& l : scene->lights()) {
    if (l.type == LightType::Sun) sun = glm::normalize(glm::vec3(l.direction));
  }
  p.set("u_sunDisk", sky.sunDisk && sun ? 1 : 0);
  p.set("u_sun", sun.value_or(glm::vec3(0, 1, 0)));
  p.set("u_fog", scene->fog().enabled ? 1 : 0);
  p.set("u_fogColor", scene->fog().color);
  p.set("u_fogDensity", scene->fog().density);
}

rt::RenderResult GpuTracer::State::runPerPixel(const gl::Program& program, int w, int firstRow, int h, int batches,
                                               const std::function<void(int)>& prepare) const {
  program.set("u_firstRow", firstRow);
  program.set("u_rows", h);
  const gl::Buffer image = gl::Buffer::create(std::size_t(w) * std::size_t(h) * sizeof(glm::vec4));
  const std::uint32_t zeros[4] = {0, 0, 0, 0};
  const gl::Buffer counters = gl::Buffer::create(sizeof(zeros), zeros);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtInput, counters.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtOutput, image.id());
  rt::RenderResult result;
  for (int batch = 0; batch < batches; ++batch) {
    if (prepare) prepare(batch);
    glNamedBufferSubData(counters.id(), 0, sizeof(zeros), zeros);
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glFinish();
    result.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::uint32_t rays[4];
    glGetNamedBufferSubData(counters.id(), 0, sizeof(rays), rays);
    result.rays += rt::RayCounters{rays[0], rays[1], rays[2]};
  }
  std::vector<glm::vec4> pixels(std::size_t(w) * std::size_t(h));
  glGetNamedBufferSubData(image.id(), 0, GLsizeiptr(pixels.size() * sizeof(glm::vec4)), pixels.data());
  result.image = rt::Framebuffer(w, h);
  for (std::size_t i = 0; i < pixels.size(); ++i) result.image.pixels[i] = glm::vec3(pixels[i]);
  return result;
}

GpuTracer::GpuTracer() : state_(std::make_unique<State>()) {}
GpuTracer::GpuTracer(GpuTracer&&) noexcept = default;
GpuTracer& GpuTracer::operator=(GpuTracer&&) noexcept = default;
GpuTracer::~GpuTracer() = default;

Result<GpuTracer> GpuTracer::create(const rt::RtScene& scene, const std::string& shaderDir, int width) {
  using detail::storage;
  GpuTracer tracer;
  State& s = *tracer.state_;
  s.scene = &scene;
  s.shaderDir = shaderDir;
  s.layout = rt::flattenScene(scene, width);
  const rt::GpuTextureSet textures = rt::flattenTextures(scene);
  const FloatImage* sky = scene.environment().image();
  // Before anything is uploaded.
  if (auto fits = fitsStorageBlocks({{"the textures", textures.texels.size() * sizeof(glm::vec4)},
                                     {"the sky image", sky ? sky->rgb.size() * sizeof(float) : 0}});
      !fits)
    return fits.error();
  s.nodes = s.layout.width == 4 ? storage(s.layout.nodes4) : storage(s.layout.nodes);
  s.leaves = storage(s.layout.leaves);
  s.order = storage(s.layout.order);
  s.instances = storage(s.layout.instances);
  s.spheres = storage(s.layout.spheres);
  s.planes = storage(s.layout.planes);
  s.triangles = storage(s.layout.triangles);
  s.materials = storage(materialsOf(scene, textures));
  s.lights = storage(lightsOf(scene));
  s.triangleAttributes = storage(s.layout.triangleAttributes);
  s.textures = storage(textures.textures);
  s.texels = storage(textures.texels);
  s.skyImage = sky ? storage(sky->rgb) : storage(std::vector<float>{});
  s.sheenTable = storage(detail::hasSheen(scene) ? engine::sheenTable().texels : std::vector<float>{});
  auto hits = gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, "rt/hits.comp"}}, detail::traceDefines(s.layout, nullptr));
  if (!hits) return hits.error();
  s.hits = std::move(hits).value();
  return tracer;
}

const rt::GpuSceneLayout& GpuTracer::layout() const { return state_->layout; }

GpuRefit::Targets GpuTracer::buffers() const {
  return GpuRefit::Targets{state_->nodes.id(), state_->leaves.id(), state_->triangles.id(), state_->instances.id()};
}

std::vector<RayAnswer> GpuTracer::trace(std::span<const RayQuery> rays) const {
  std::vector<RayAnswer> answers(rays.size());
  if (rays.empty()) return answers;
  const State& s = *state_;
  const gl::Buffer in = gl::Buffer::create(rays.size_bytes(), rays.data());
  const gl::Buffer out = gl::Buffer::create(answers.size() * sizeof(RayAnswer));
  s.bindScene(s.hits);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtInput, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtOutput, out.id());
  glUniform1ui(s.hits.location("u_count"), GLuint(rays.size()));
  glDispatchCompute(GLuint((rays.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(answers.size() * sizeof(RayAnswer)), answers.data());
  return answers;
}

Result<rt::RenderResult> GpuTracer::render(const rt::RenderSettings& settings) const {
  return render(settings, 0, settings.height);
}

Result<rt::RenderResult> GpuTracer::render(const rt::RenderSettings& settings, int firstRow, int rows) const {
  if (const std::string why = unsupported(*state_->scene, settings); !why.empty()) return makeError(why);
  if (firstRow < 0 || rows < 1 || firstRow + rows > settings.height) {
    return makeError("rows " + std::to_string(firstRow) + " to " + std::to_string(firstRow + rows) +
                     " are not in an image " + std::to_string(settings.height) + " high");
  }
  return settings.method == rt::Method::Path ? renderPath(settings, firstRow, rows)
                                             : renderWhitted(settings, firstRow, rows);
}

Result<rt::RenderResult> GpuTracer::renderWhitted(const rt::RenderSettings& settings, int firstRow, int rows) const {
  const State& s = *state_;
  const rt::RtScene& scene = *s.scene;
  const int maxDepth = std::max(0, settings.maxDepth);
  auto found = s.whitted.find(maxDepth);
  if (found == s.whitted.end()) {
    std::vector<std::string> defines = detail::traceDefines(s.layout, &scene);
    defines.push_back("RT_MAX_DEPTH " + std::to_string(maxDepth));
    auto program = gl::Program::build(s.shaderDir, {{GL_COMPUTE_SHADER, "rt/whitted.comp"}}, defines);
    if (!program) return program.error();
    found = s.whitted.emplace(maxDepth, std::move(program).value()).first;
  }
  const gl::Program& p = found->second;
  s.bindScene(p);
  // The sheen's albedo table (RT_SHEEN_TABLE's), uploaded once with the scene.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtEnvironment, s.sheenTable.id());
  p.set("u_sheenTable", 0);
  s.setView(p, settings);
  const int spp = std::max(1, settings.samplesPerPixel);
  const glm::ivec2 strata = rt::detail::strataFor(spp);
  glUniform2i(p.location("u_strata"), strata.x, strata.y);
  p.set("u_spp", spp);
  p.set("u_maxDepth", maxDepth);
  // A tree of mirror and transmitted rays, 2^(maxDepth + 1) - 1 at most.
  p.set("u_rayBound", int((std::int64_t(1) << std::min(maxDepth + 1, 30)) - 1));
  p.set("u_lastPass", 63);
  p.set("u_shadowSamples", settings.shadowSamples);
  p.set("u_lightCount", int(scene.lights().size()));
  p.set("u_pbr", scene.render().shading == Shading::Pbr ? 1 : 0);
  p.set("u_ambientSky", scene.ambientSky());
  p.set("u_ambientGround", scene.ambientGround());
  p.set("u_coneSpread", rt::pixelConeSpread(scene.camera().fovyDegrees, settings.height, spp));
  return s.runPerPixel(p, settings.width, firstRow, rows);
}

}  // namespace engine::gpurt
