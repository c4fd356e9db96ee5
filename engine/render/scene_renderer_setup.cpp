// SceneRenderer at load: settings, programs, passes, targets.
#include "render/scene_renderer_impl.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "core/srgb_curve.h"
#include "render/pass_state.h"
#include "render/render_target.h"
#include "render/textures.h"

namespace engine {

Status SceneRenderer::Impl::init(std::shared_ptr<Scene> source, const SceneRenderOptions& options) {
  shaderDir = options.shaderDir;
  render = scene.render;
  if (options.msaaOverride > 0) render.msaa = options.msaaOverride;
  render.skinning = options.skinningOverride.value_or(render.skinning);
  render.lodPixels = options.lodPixelsOverride.value_or(render.lodPixels);
  render.gpuCulling = options.gpuCullingOverride.value_or(render.gpuCulling);
  cullDepthMargin = options.gpuCullingDepthMargin;
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

  lights = compileLights(scene);
  const bool sunShadows = lights.sun >= 0 && scene.lights[size_t(lights.sun)].shadows;
  const bool pointShadows = !lights.points.empty() && scene.lights[size_t(lights.points[0])].shadows;

  // The lights' counts are compile-time (common/direct_light.glsl says why).
  std::vector<std::string> defines = {"SUN_LIGHT " + std::to_string(lights.sun >= 0 ? 1 : 0),
                                      "POINT_LIGHTS " + std::to_string(lights.points.size())};
  if (render.shading == Shading::Classic) defines.push_back("CLASSIC 1");
  if (sunShadows) defines.push_back("SUN_SHADOWS 1");
  const bool sunFarShadows = sunShadows && scene.terrain.enabled;
  if (sunFarShadows) defines.push_back("SUN_FAR_SHADOWS 1");
  if (pointShadows) defines.push_back("POINT_SHADOWS 1");
  // The PCF kernel too, so that its loops unroll (common/shadows.glsl).
  if (sunShadows || pointShadows) defines.push_back("PCF_RADIUS " + std::to_string(pcfRadius));
  if (scene.fog.enabled) defines.push_back("FOG 1");
  // What of a fragment's position the lighting reads beyond its direction: the
  // deferred characters' surface then keeps its distance (common/surface.glsl).
  const bool surfacePosition = sunShadows || pointShadows || !lights.points.empty() || scene.fog.enabled;
  if (surfacePosition) defines.push_back("SURFACE_POSITION 1");
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
      scene, options.reflectionProbeOverride >= 0 ? options.reflectionProbeOverride : render.reflectionProbe);
  if (!probePass) return probePass.error();
  probes = std::move(probePass).value();
  if (probes) defines.push_back("REFLECTION_PROBES 1");
  directOutput = !options.hdrTarget && needsNoHdrTarget(*source);
  if (directOutput) {
    const std::vector<std::string> display = displayDefines();
    defines.insert(defines.end(), display.begin(), display.end());
  }

  if (render.output != OutputCurve::Gamma22) makeDisplayTable();
  GpuSceneOptions upload;
  upload.shaderDir = shaderDir;
  upload.skinning = render.skinning;
  upload.manyPasses = pointShadows || probes;
  upload.levelsOfDetail = render.lodPixels > 0.0;
  upload.skinModeOverride = options.skinModeOverride;
  if (probes) upload.probeShapes = probes->shapes();
  auto uploaded = GpuScene::create(std::move(source), scene, upload);
  if (!uploaded) return uploaded.error();
  gpu = std::move(uploaded).value();
  draws = std::make_unique<SceneDraws>(*gpu, scene,
                                       std::make_unique<ShaderVariants>(shaderDir, "scene.vert", "scene.frag", defines),
                                       stats);
  if (auto s = makeSky(); !s) return s;
  if (auto s = makePost(); !s) return s;
  emptyVao = gl::VertexArray::create();
  if (auto s = makeEnvironmentLighting(); !s) return s;

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
  if (auto s = makeCuller(); !s) return s;

  if (sunShadows) {
    auto made = SunShadowPass::create(scene.lights[size_t(lights.sun)], render.shadowMapSize, sunFarShadows, *gpu,
                                      *draws, terrain.get(), stats);
    if (!made) return made.error();
    sun = std::move(made).value();
  }
  if (pointShadows) {
    auto made = PointShadowPass::create(scene.lights[size_t(lights.points[0])].position, render.shadowMapSize,
                                        std::max(1.0, scene.camera.farPlane), *draws);
    if (!made) return made.error();
    point = std::move(made).value();
  }
  if (auto s = draws->buildVariants(sunShadows || pointShadows, sunFarShadows, surfaces); !s) return s;
  draws->link({sun.get(), point.get(), probes.get(), surfaces.get()});
  frame = std::make_unique<FrameUniforms>(scene, lights, pcfRadius, sun.get(), point.get(),
                                          environmentLighting ? &*environmentLighting : nullptr);
  return Ok{};
}

// The sky pass's programs: the gradient, or the SKY_IMAGE variant with its texture,
// uploaded once; linear (HDR_OUTPUT) for the HDR target and the environment cube,
// and with directOutput a second that writes the view's display values.
Status SceneRenderer::Impl::makeSky() {
  if (!scene.sky.enabled) return Ok{};
  std::vector<std::string> variant;
  if (gpu->skyImage()) variant.push_back("SKY_IMAGE 1");
  const auto build = [&](std::vector<std::string> defines, gl::Program& out) -> Status {
    defines.insert(defines.end(), variant.begin(), variant.end());
    auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}}, defines);
    if (!program) return program.error();
    out = std::move(program).value();
    return Ok{};
  };
  if (auto s = build({"HDR_OUTPUT 1"}, sky); !s) return s;
  return directOutput ? build(displayDefines(), skyDisplay) : Ok{};
}

// The one post variant these settings need (post.frag says why not uniforms);
// none where the fragment shaders write display values themselves.
Status SceneRenderer::Impl::makePost() {
  if (directOutput) return Ok{};
  std::vector<std::string> defines{"SUPERSAMPLE " + std::to_string(render.supersample),
                                   "TONE_MAP " + std::to_string(int(render.toneMap))};
  if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "post.vert"}, {GL_FRAGMENT_SHADER, "post.frag"}}, defines);
  if (!program) return program.error();
  post = std::move(program).value();
  return Ok{};
}

// The environment as the path tracer sees it (the sky without its sun disk, or the
// background), drawn into a cube map once: the scene's sky never changes while it
// is loaded. From it the SH irradiance, the BRDF table and, for IBL, the
// prefiltered chain; the cube itself is dropped.
Status SceneRenderer::Impl::makeEnvironmentLighting() {
  if (render.shading == Shading::Classic || ambient == Ambient::Hemisphere) return Ok{};
  const auto start = std::chrono::steady_clock::now();
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  const gl::Texture environment = makeCubeMap(iblSize, 0);
  const gl::Framebuffer fbo = gl::Framebuffer::create();
  // Any 90-degree projection will do: sky.vert takes only directions from it.
  const glm::dmat4 projection = glm::perspective(glm::half_pi<double>(), 1.0, 0.1, 10.0);
  const glm::vec3 background = scene.sky.background;
  glViewport(0, 0, iblSize, iblSize);
  applyPassState(kSkyPass);
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, environment.id(), 0, face);
    if (auto s = fbo.check("ibl-environment"); !s) return s;
    fbo.bind();
    glClearColor(background.r, background.g, background.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (scene.sky.enabled) {
      drawSky(sky, projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]), false);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  applyPassState(kCallerState);
  environment.generateMipmaps();
  auto lighting = EnvironmentLighting::create(shaderDir, environment, iblSize, ambient);
  if (!lighting) return makeError(scene.path + ": /render/ambient: " + lighting.error().message);
  environmentLighting = std::move(lighting).value();
  glFinish();
  iblMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
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
    for (const MaterialData& m : asset->model.materials)
      if (m.alphaMode == AlphaMode::Blend || m.layers.transmissive()) return false;
  }
  return true;
}

// The table common/output.glsl reads: ACES and the curve in one where the fragment
// shaders write display values after ACES (its targetColor), else the curve's.
void SceneRenderer::Impl::makeDisplayTable() {
  const DisplayTable& table = directOutput && render.toneMap == ToneMap::Aces ? acesSrgbTable() : srgbTable();
  displayTableTexels = gl::Buffer::create(table.texels.size() * sizeof(float), table.texels.data(), 0);
  displayTable = gl::Texture::ofBuffer(displayTableTexels, GL_RG32F);
}

std::vector<std::string> SceneRenderer::Impl::displayDefines() const {
  char exposure[32];
  std::snprintf(exposure, sizeof(exposure), "EXPOSURE %.9g", double(render.exposure));  // the float's exact value
  std::vector<std::string> defines{"DIRECT_OUTPUT 1", "TONE_MAP " + std::to_string(int(render.toneMap)), exposure};
  if (render.output == OutputCurve::Gamma22) defines.push_back("OUTPUT_GAMMA22 1");
  return defines;
}

Status SceneRenderer::Impl::makeTarget(int width, int height) {
  const int w = width * render.supersample, h = height * render.supersample;
  if (w == targetWidth && h == targetHeight && drawFbo) return Ok{};
  targetWidth = w;
  targetHeight = h;
  hdr = gl::Texture::create2D(directOutput ? GL_RGBA8 : GL_RGBA16F, w, h, 1);
  hdr.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  hdr.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const int samples = render.msaa > 1 ? render.msaa : 0;
  depth = gl::Renderbuffer::create(depthFormat(), w, h, samples);
  drawFbo = gl::Framebuffer::create();
  borrowedColour = 0;
  if (samples > 0) {
    msaaColor = gl::Renderbuffer::create(GL_RGBA16F, w, h, samples);
    drawFbo.attach(GL_COLOR_ATTACHMENT0, msaaColor);
    resolveFbo = gl::Framebuffer::create();
    resolveFbo.attach(GL_COLOR_ATTACHMENT0, hdr);
  } else {
    drawFbo.attach(GL_COLOR_ATTACHMENT0, hdr);
  }
  drawFbo.attach(stencilled() ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth);
  if (surfaces) surfaces->attach(drawFbo, w, h);
  if (terrain && terrain->deferred()) terrain->attach(drawFbo, w, h);
  if (auto s = drawFbo.check(directOutput ? "scene-display" : "scene-hdr"); !s) return s;
  if (gpu->refracts()) {
    const int levels = 1 + int(std::floor(std::log2(double(std::max(w, h)))));
    transmissionSource = gl::Texture::create2D(GL_RGBA16F, w, h, levels);
    transmissionSource.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    transmissionSource.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    transmissionSource.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    transmissionSource.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    transmissionFbo = gl::Framebuffer::create();
    transmissionFbo.attach(GL_COLOR_ATTACHMENT0, transmissionSource);
    if (auto s = transmissionFbo.check("transmission-source"); !s) return s;
  }
  return samples > 0 ? resolveFbo.check("scene-hdr-resolve") : Status(Ok{});
}

}  // namespace engine
