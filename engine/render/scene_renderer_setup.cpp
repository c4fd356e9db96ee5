// SceneRenderer at load: the settings, then the passes the scene needs.
#include "render/scene_renderer_impl.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "render/render_target.h"
#include "scene/terrain_mesh.h"

namespace engine {

Status SceneRenderer::Impl::init(std::shared_ptr<Scene> source, const SceneRenderOptions& options,
                                 std::shared_ptr<GpuScene> shared) {
  const std::string& shaderDir = options.shaderDir;
  render = scene.render;
  if (options.msaaOverride > 0) render.msaa = options.msaaOverride;
  render.skinning = options.skinningOverride.value_or(render.skinning);
  render.lodPixels = options.lodPixelsOverride.value_or(render.lodPixels);
  render.gpuCulling = options.gpuCullingOverride.value_or(render.gpuCulling);
  render.shading = options.shadingOverride.value_or(render.shading);
  if (options.exposureOverride > 0.0f) render.exposure = options.exposureOverride;
  render.toneMap = options.toneMapOverride.value_or(render.toneMap);
  render.output = options.outputOverride.value_or(render.output);
  rotations = options.rotations;
  if (options.supersampleOverride > 0) render.supersample = options.supersampleOverride;
  if (options.shadowMapOverride > 0) render.shadowMapSize = options.shadowMapOverride;
  if (options.pcfKernelOverride > 0) {
    render.pcfKernel = options.pcfKernelOverride;
    render.shadowFilter = options.pcfKernelOverride > 1 ? ShadowFilter::Pcf : ShadowFilter::Hard;
  }
  pcfRadius = render.shadowFilter == ShadowFilter::Hard ? 0 : render.pcfKernel / 2;
  // Checked before anything is built: a scene may ask for more samples (up to 16)
  // than this GL offers, and a frame without its target would draw nothing.
  if (const int most = RenderTarget::maxSamples(); render.msaa > most) {
    return makeError(scene.path + ": /render/msaa: " + std::to_string(render.msaa) +
                     " samples asked, this GL offers up to " + std::to_string(most));
  }

  // The environment's lights (the models' included), not the scene file's.
  CompiledLights lights = compileLights(source->environment().lights);
  if (lights.dropped > 0) {
    logWarning(scene.path + ": " + std::to_string(lights.dropped) + " light(s) not drawn: the rasterizer draws a sun and " +
               std::to_string(kMaxPointLights) + " other lights (the tracers draw every light)");
  }
  const std::optional<LightDesc> sunLight = lights.sun;
  const bool sunShadows = sunLight && sunLight->shadows;
  const bool pointShadows = lights.pointShadows();

  // The lights' counts are compile-time (common/direct_light.glsl says why).
  std::vector<std::string> defines = {"SUN_LIGHT " + std::to_string(sunLight ? 1 : 0),
                                      "POINT_LIGHTS " + std::to_string(lights.others.size())};
  if (render.shading == Shading::Classic) defines.push_back("CLASSIC 1");
  if (sunShadows) defines.push_back("SUN_SHADOWS 1");
  const bool sunFarShadows = sunShadows && scene.terrain.enabled;
  if (sunFarShadows) defines.push_back("SUN_FAR_SHADOWS 1");
  if (pointShadows) defines.push_back("POINT_SHADOWS 1");
  if (lights.spots()) defines.push_back("SPOT_LIGHTS 1");
  // The PCF kernel too, so that its loops unroll (common/shadows.glsl).
  if (sunShadows || pointShadows) defines.push_back("PCF_RADIUS " + std::to_string(pcfRadius));
  if (scene.fog.enabled) defines.push_back("FOG 1");
  if (scene.atmosphere.enabled) defines.push_back("AERIAL_PERSPECTIVE 1");
  // What of a fragment's position the lighting reads beyond its direction: the
  // deferred characters' surface then keeps its distance (common/surface.glsl).
  const bool surfacePosition =
      sunShadows || pointShadows || !lights.others.empty() || scene.fog.enabled || scene.atmosphere.enabled;
  if (surfacePosition) defines.push_back("SURFACE_POSITION 1");
  int iblSize = 0;
  if (render.shading == Shading::Pbr) {
    ambient = options.ambientOverride.value_or(ambientOf(scene));
    iblSize = options.iblSizeOverride > 0 ? options.iblSizeOverride : render.iblSize;
    if (ambient == Ambient::Sh) defines.push_back("AMBIENT_SH 1");
    if (ambient == Ambient::Ibl) defines.push_back("AMBIENT_IBL 1");
  }
  debugView = options.debugView;
  if (debugView != DebugView::None) {
    // The value as it is: no exposure, no tone map (post.frag's TONE_MAP 0 clamps).
    defines.push_back("DEBUG_VIEW " + std::to_string(int(debugView)));
    render.exposure = 1.0f;
    render.toneMap = ToneMap::None;
  }
  auto probePass = ReflectionProbePass::create(
      scene, source->materials(),
      options.reflectionProbeOverride >= 0 ? options.reflectionProbeOverride : render.reflectionProbe);
  if (!probePass) return probePass.error();
  probes = std::move(probePass).value();
  if (probes) defines.push_back("REFLECTION_PROBES 1");
  const bool directOutput = !options.hdrTarget && needsNoHdrTarget(*source);
  const std::vector<std::string> display = directOutput ? displayDefines(render) : std::vector<std::string>{};
  defines.insert(defines.end(), display.begin(), display.end());

  GpuSceneOptions upload;
  upload.shaderDir = shaderDir;
  upload.skinning = render.skinning;
  upload.manyPasses = pointShadows || probes;
  upload.levelsOfDetail = render.lodPixels > 0.0;
  upload.skinModeOverride = options.skinModeOverride;
  if (probes) upload.probeShapes = probes->shapes();
  if (shared && &shared->source() == source.get() && shared->options() == upload) {
    gpu = std::move(shared);
  } else {
    auto uploaded = GpuScene::create(std::move(source), scene, upload);
    if (!uploaded) return uploaded.error();
    gpu = std::move(uploaded).value();
  }
  draws = std::make_unique<SceneDraws>(*gpu, scene,
                                       std::make_unique<ShaderVariants>(shaderDir, defines),
                                       stats);
  // Programs are built in this order (their names order the draws' sort keys).
  auto skyPass = SkyPass::create(shaderDir, scene, sunLight ? &*sunLight : nullptr, gpu->skyImage(), display, stats);
  if (!skyPass) return skyPass.error();
  sky = std::move(skyPass).value();
  auto outputPass = OutputPass::create(shaderDir, render, directOutput, stats);
  if (!outputPass) return outputPass.error();
  output = std::move(outputPass).value();
  if (render.shading == Shading::Pbr && ambient != Ambient::Hemisphere) {
    if (auto s = sky->buildEnvironment(shaderDir, ambient, iblSize); !s) return s;
  }

  if (terrain::Terrain* field = gpu->source().terrain()) {
    const TerrainPassSettings settings{terrainErrorTarget(scene, options.terrainErrorOverride),
                                       render.msaa <= 1 && !options.forwardTerrain, options.planeOcclusion,
                                       options.planeOcclusionPixelMargin};
    auto made = TerrainPass::create(shaderDir, *field, defines, settings, scene, *gpu, *draws, stats);
    if (!made) return made.error();
    terrain = std::move(made).value();
  }
  // The deferred characters' groups are known once their programs are (buildVariants).
  if (render.msaa <= 1 && !options.forwardCharacters) {
    surfaces = std::make_unique<CharacterSurfacePass>(surfacePosition, terrain && terrain->deferred(), *gpu, *draws,
                                                      stats);
  }
  if (render.gpuCulling) {
    auto made = GpuCullPass::create(shaderDir, scene.path, depthFormat(), render.msaa <= 1,
                                    options.gpuCullingDepthMargin, *gpu, *draws, terrain.get(), stats);
    if (!made) return made.error();
    culling = std::move(made).value();
  }
  if (sunShadows) {
    auto made = SunShadowPass::create(*sunLight, render.shadowMapSize, sunFarShadows, *gpu, *draws, terrain.get(),
                                      stats);
    if (!made) return made.error();
    sun = std::move(made).value();
  }
  if (pointShadows) {
    auto made = PointShadowPass::create(lights.others[0].position, render.shadowMapSize,
                                        std::max(1.0, scene.camera.farPlane), *draws);
    if (!made) return made.error();
    point = std::move(made).value();
  }
  if (auto s = draws->buildVariants(sunShadows || pointShadows, sunFarShadows, surfaces ? &surfaces->groups() : nullptr);
      !s) {
    return s;
  }
  if (surfaces && surfaces->groups().empty()) surfaces.reset();  // no work for it (SurfaceGroups::finish)
  draws->link(drawSources());
  frame = std::make_unique<FrameUniforms>(scene, std::move(lights), pcfRadius, sun.get(), point.get(),
                                          sky->environment());
  if (gpu->refracts()) transmission = std::make_unique<TransmissionPass>();
  world = std::make_unique<WorldPass>(*draws, *sky, *output, terrain.get(), surfaces.get(), transmission.get(),
                                      culling.get());
  return Ok{};
}

DrawSources SceneRenderer::Impl::drawSources() const {
  DrawSources sources;
  if (sun || point) {
    sources.shadowUniforms = [sun = sun.get(), point = point.get()](const gl::Program& program) {
      if (sun) sun->setUniforms(program);
      if (point) point->setUniforms(program);
    };
  }
  if (sun) {
    sources.nearSunCovers = [sun = sun.get()](const glm::dvec3& lo, const glm::dvec3& hi) {
      return sun->nearCovers(lo, hi);
    };
  }
  if (probes) sources.probeCube = [probes = probes.get()](int probe) -> const gl::Texture& { return probes->cube(probe); };
  sources.surfaces = surfaces ? &surfaces->groups() : nullptr;
  return sources;
}

// Whether the frame can skip the HDR target and the post pass (issue 14: a scene
// with no HDR effect pays for none). Exposure, the tone map and the curve are per
// pixel, so the fragment shaders apply them as well as a post pass (the sky's view
// variant too) and write display values (common/output.glsl); the bytes differ from
// the post pass's by at most one level, where it rounded the radiance to half floats
// first (DirectOutput tests). What needs the linear image: MSAA's resolve and
// supersampling's average (both before the tone map), blending and transmission (in
// linear light), the probes' cubes (linear radiance for the scene's own shaders), the
// debug views (their values as they are).
bool SceneRenderer::Impl::needsNoHdrTarget(const Scene& source) const {
  if (render.msaa > 1 || render.supersample > 1) return false;
  if (probes || debugView != DebugView::None) return false;
  for (const auto& asset : source.assets()) {
    for (const SceneMaterial& m : asset->materials)
      if (m.blends() || m.transmissive()) return false;
  }
  return true;
}

}  // namespace engine
