// GpuTracer's path tracer (shaders/rt/pathtrace.comp): the lights and the
// environment's sampling tables as the CPU's path tracer prepares them
// (raytrace/path_lights.h's preparePathLights), uploaded, and the samples in
// batches, a dispatch each, every batch adding to the pixels' sums.
#include <algorithm>
#include <cstddef>
#include <span>

#include "gl/bindings.h"
#include "gputrace/gpu_tracer.h"
#include "gputrace/gpu_tracer_impl.h"
#include "core/sheen_table.h"
#include "raytrace/path_lights.h"
#include "raytrace/ray_cone.h"

namespace engine::gpurt {
namespace {

// std430 twin of pathtrace.comp's PtLight: a PathLight, its position and edges in
// double as the CPU keeps them (an area light's sample point is formed in double
// and rounded once).
struct GpuPathLight {
  glm::ivec4 typeShadowsFalloff;
  glm::vec4 powerArea;        // power; w: area
  glm::vec4 directionCosMax;  // direction; w: cosMax
  glm::vec4 radiance;
  glm::vec4 normal;
  glm::vec4 cone;  // cosOuter, cosInner (also what std430's 32-byte dvec4 alignment asks)
  glm::dvec4 position, edgeU, edgeV;
};
static_assert(sizeof(GpuPathLight) == 192 && offsetof(GpuPathLight, position) == 96);

std::vector<GpuPathLight> pathLightsOf(const rt::PathLights& lights) {
  std::vector<GpuPathLight> out;
  for (const rt::PathLight& l : lights.lights) {
    const int type = l.type == LightType::Sun ? 0 : l.type == LightType::Area ? 2 : 1;
    out.push_back(GpuPathLight{glm::ivec4(type, l.shadows ? 1 : 0, l.falloff ? 1 : 0, 0), glm::vec4(l.power, l.area),
                               glm::vec4(l.direction, l.cosMax), glm::vec4(l.radiance, 0.0f), glm::vec4(l.normal, 0.0f),
                               glm::vec4(l.cosOuter, l.cosInner, 0.0f, 0.0f), glm::dvec4(l.position, 0.0), glm::dvec4(l.edgeU, 0.0),
                               glm::dvec4(l.edgeV, 0.0)});
  }
  return out;
}

// The environment's Distribution2D in the order rt/environment_light.glsl reads it:
// the marginal's weights, CDF and integral, then every row's weights, every row's
// CDF and every row's integral. Empty when the environment is black.
std::vector<float> environmentTables(const rt::EnvironmentLight& environment) {
  std::vector<float> out;
  if (environment.black()) return out;
  const rt::Distribution2D& d = environment.distribution();
  const auto append = [&out](std::span<const float> values) { out.insert(out.end(), values.begin(), values.end()); };
  append(d.marginal().func());
  append(d.marginal().cdf());
  out.push_back(d.marginal().integral());
  for (int y = 0; y < d.height(); ++y) append(d.row(y).func());
  for (int y = 0; y < d.height(); ++y) append(d.row(y).cdf());
  for (int y = 0; y < d.height(); ++y) out.push_back(d.row(y).integral());
  return out;
}

// Samples per dispatch: few enough that a dispatch's ray counters (32 bits, what a
// shader's atomics add) cannot overflow, even if every path went the whole depth
// with a shadow ray per light and the environment at every vertex, and that no
// dispatch runs for minutes (a GPU's watchdog ends those).
int samplesPerBatch(const rt::RenderSettings& settings, std::size_t lights) {
  constexpr double kCounterLimit = 4.0e9;
  constexpr int kMostPerBatch = 16;
  const double raysPerSample = double(std::max(0, settings.maxDepth) + 2) * double(lights + 2);
  const double pixels = double(settings.width) * double(settings.height);
  return std::clamp(int(kCounterLimit / (pixels * raysPerSample)), 1, kMostPerBatch);
}

}  // namespace

Result<rt::RenderResult> GpuTracer::renderPath(const rt::RenderSettings& settings, int firstRow, int rows) const {
  const State& s = *state_;
  const rt::RtScene& scene = *s.scene;
  if (!s.path) {
    auto program = gl::Program::build(s.shaderDir, {{GL_COMPUTE_SHADER, "rt/pathtrace.comp"}}, detail::traceDefines(s.layout, &scene));
    if (!program) return program.error();
    s.path = std::move(program).value();
  }
  const gl::Program& p = *s.path;
  // Prepared for each render, as Integrator prepares them: the sky may have changed.
  const std::shared_ptr<const rt::PathLights> lights = rt::preparePathLights(scene);
  const gl::Buffer lightBuffer = detail::storage(pathLightsOf(*lights));
  // The sheen's albedo table after the environment's, where a material has a sheen.
  std::vector<float> tables = environmentTables(lights->environment);
  const int sheenOffset = int(tables.size());
  if (detail::hasSheen(scene)) {
    const std::vector<float>& sheen = engine::sheenTable().texels;
    tables.insert(tables.end(), sheen.begin(), sheen.end());
  }
  const gl::Buffer environment = detail::storage(tables);
  s.bindScene(p);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtLights, lightBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtEnvironment, environment.id());
  s.setView(p, settings);
  p.set("u_lightCount", int(lights->lights.size()));
  p.set("u_maxDepth", settings.maxDepth);
  p.set("u_rouletteDepth", settings.rouletteDepth);
  p.set("u_pbr", scene.render().shading == Shading::Pbr ? 1 : 0);
  p.set("u_coneSun", lights->coneSun ? 1 : 0);
  p.set("u_sheenTable", sheenOffset);
  p.set("u_coneSpread", rt::pixelConeSpread(scene.camera().fovyDegrees, settings.height,
                                            settings.totalSamples > 0 ? settings.totalSamples : settings.samplesPerPixel));
  const rt::Distribution2D& d = lights->environment.distribution();
  glUniform2i(p.location("u_envSize"), d.width(), d.height());
  p.set("u_envBlack", lights->environment.black() ? 1 : 0);
  // Samples [first, first + spp) in batches; the kernel adds each to the pixel's sum
  // in the CPU's order, and the mean is taken here as renderPixel takes it.
  const int first = std::max(0, settings.firstSample), spp = std::max(1, settings.samplesPerPixel);
  const int batch = samplesPerBatch(settings, lights->lights.size());
  rt::RenderResult result = s.runPerPixel(p, settings.width, firstRow, rows, (spp + batch - 1) / batch, [&](int b) {
    p.set("u_firstSample", first + b * batch);
    p.set("u_spp", std::min(batch, spp - b * batch));
    p.set("u_accumulate", b > 0 ? 1 : 0);
  });
  for (glm::vec3& pixel : result.image.pixels) pixel /= float(spp);
  return result;
}

}  // namespace engine::gpurt
