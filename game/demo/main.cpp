// demo: the engine's showcase. Draws a scene file (assets/scenes/demo.json by
// default) in a window; with --offscreen it renders N frames at a fixed step
// through EGL or OSMesa and writes the last one to a PNG.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include <fstream>
#include <nlohmann/json.hpp>

#include "app/cli.h"
#include "asset/scene_file.h"
#include "core/float_image_io.h"
#include "gpu_raytrace.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/describe.h"
#include "raytrace/progress_bar.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"
#include "raytrace_game.h"
#include "scene_game.h"
#include "soak_game.h"

namespace {

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "demo: %s\n", message.c_str());
  return code;
}

struct RaytraceOptions {
  std::string precision = "float";
  std::string device = "cpu";
  bool animate = false;
  engine::rt::RenderSettings settings;
};

// The traced frame as its name asks: encoded (PNG), or the linear framebuffer.
engine::Status writeTraced(const std::string& path, const engine::rt::RaytraceRun& run) {
  if (!engine::floatFormatForName(path)) return engine::writePng(path, run.image);
  return engine::writeFloatImage(path, engine::rt::toFloatImage(run.result.image));
}

// Offscreen ray tracing needs no GL context on the CPU: trace, encode, write. On the
// GPU (--device gpu) it opens an offscreen one.
int runRaytraceOffscreen(const engine::SceneDesc& scene, const engine::CommonOptions& options,
                         engine::rt::RenderSettings settings, bool gpu) {
  engine::rt::ProgressBar bar;
  settings.progress = [&bar](const engine::rt::RenderProgress& p) { return bar.update(p); };
  const double time = options.run.time.value_or(0.0);
  auto run = gpu ? demo::gpuRaytraceScene(scene, time, settings, engine::chosenBackend(options), options.shaderDir)
                 : engine::rt::raytraceScene(scene, time, settings);
  if (!run) return fail(engine::kExitBadInput, run.error().message);
  if (auto s = writeTraced(options.run.screenshot, *run); !s) return fail(engine::kExitBadInput, s.error().message);
  const auto& r = run->result.rays;
  const double mrays = run->result.seconds > 0.0 ? double(r.total()) / run->result.seconds / 1e6 : 0.0;
  std::fprintf(stderr, "%s%s %dx%d, spp %d: %.3f s, %.2f Mrays/s (%llu primary, %llu shadow, %llu %s); "
               "%d meshes, %d triangles, BVH %.1f ms\n",
               settings.method == engine::rt::Method::Path ? "path traced" : "ray traced", gpu ? " on the GPU" : "", settings.width,
               settings.height, settings.samplesPerPixel, run->result.seconds, mrays, (unsigned long long)r.primary,
               (unsigned long long)r.shadow, (unsigned long long)r.reflection,
               settings.method == engine::rt::Method::Path ? "bounce" : "reflection",
               run->build.meshes, run->build.triangles, run->build.bvhSeconds * 1e3);
  if (!options.run.benchFile.empty()) {
    const bool path = settings.method == engine::rt::Method::Path;
    nlohmann::json j = {{"mode", path ? "pathtrace" : "raytrace"}, {"device", gpu ? "gpu" : "cpu"}, {"seconds", run->result.seconds}, {"mrays_per_second", mrays},
                        {"rays", {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection}}},
                        {"width", settings.width}, {"height", settings.height}, {"spp", settings.samplesPerPixel},
                        {"shadow_samples", settings.shadowSamples}, {"threads", settings.threads},
                        {"bvh_build_ms", run->build.bvhSeconds * 1e3}, {"command", options.run.command}};
    std::ofstream(options.run.benchFile) << j.dump(2) << "\n";
  }
  std::printf("%s\n", options.run.screenshot.c_str());
  return 0;
}

// --describe in the tracers' modes: what the tracer builds for the scene (and on the
// GPU its kernel's variant and buffers), or why the GPU refuses it (exit 2).
int describeRaytrace(const engine::SceneDesc& desc, const engine::CommonOptions& options,
                     const engine::rt::RenderSettings& settings, bool gpu) {
  auto scene = engine::rt::buildRtScene(desc, options.run.time.value_or(0.0), settings.height);
  if (!scene) return fail(engine::kExitBadInput, scene.error().message);
  std::fputs(engine::rt::describe(*scene, settings).c_str(), stdout);
  if (!gpu) return 0;
  if (const std::string why = engine::gpurt::unsupported(*scene, settings); !why.empty()) {
    return fail(engine::kExitBadInput, "--device gpu: " + why);
  }
  std::fputs(engine::gpurt::describe(*scene, settings).c_str(), stdout);
  return 0;
}

// The soak: frames until the time is up (however many that is), then the samples'
// summary; RSS and live GL objects are for the caller to judge.
int runSoak(const std::string& scenePath, const engine::SceneRenderOptions& render, double seconds, double reload,
            engine::Backend backend, engine::RunOptions run) {
  demo::SoakGame game(scenePath, render, seconds, reload);
  run.frames = backend == engine::Backend::Window ? 0 : std::numeric_limits<int>::max();
  run.time.reset();
  const auto status = backend == engine::Backend::Window ? engine::runWindow(game, run)
                                                         : engine::runHeadless(backend, game, run);
  if (!status) return fail(engine::kExitBadInput, status.error().message);
  std::fputs(game.report().c_str(), stderr);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Interactive OpenGL demo engine: renders a scene in a window or offscreen to PNG.", "demo"};
  engine::CommonOptions options;
  engine::SceneRenderOptions render;
  std::string scenePath;
  bool describe = false;
  app.add_option("scene", scenePath, "Scene file (JSON); default: assets/scenes/demo.json");
  engine::addCommonOptions(app, options);
  app.add_option("--supersample", render.supersampleOverride, "Render N x N times larger and average down")
      ->check(CLI::Range(1, 4));
  app.add_option("--shadow-map", render.shadowMapOverride, "Shadow map size in texels")->check(CLI::Range(64, 8192));
  app.add_option("--pcf", render.pcfKernelOverride, "PCF kernel width (odd; 1 = hard shadows)")
      ->check(CLI::IsMember({1, 3, 5, 7, 9}));
  app.add_option("--reflection-probe", render.reflectionProbeOverride,
                 "Cube map size of the mirrors' reflection probes (0: no reflections)")
      ->check(CLI::Range(0, 2048));
  std::string ambient;
  app.add_option("--ambient", ambient,
                 "PBR ambient: hemisphere (two sky colours), sh (SH irradiance of the sky) or ibl (split-sum "
                 "image-based lighting); default: the scene's render.ambient, ibl under a sky")
      ->check(CLI::IsMember(engine::ambientNames()));
  app.add_option("--ibl-size", render.iblSizeOverride, "Cube map size of the environment for sh and ibl")
      ->check(CLI::Range(16, 1024));
  std::string skinning;
  app.add_option("--skinning", skinning,
                 "How characters deform: vertex (in every pass's vertex shader), compute (once per pose into a "
                 "skin cache that every pass draws) or auto (the cache for morph targets, dual quaternions and "
                 "skins drawn by more than two passes); default: the scene's render.skinning, auto")
      ->check(CLI::IsMember(engine::skinningNames()));
  double lodPixels = -1.0;
  app.add_option("--lod-pixels", lodPixels,
                 "Models' levels of detail (simplified meshes, made at load): drawn where their error is within "
                 "this many pixels on screen; 0 draws every mesh in full; default: the scene's render.lod_pixels, 0")
      ->check(CLI::Range(0.0, 64.0));
  std::string gpuCulling;
  app.add_option("--gpu-culling", gpuCulling,
                 "Cull the main view's meshes per instance and per cluster of 128 triangles in a compute shader, "
                 "against the frustum and the depth drawn so far (changes no pixel); default: the scene's "
                 "render.gpu_culling, off")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_flag("--hdr-target", render.hdrTarget,
               "Keep the HDR target and the post pass where the scene needs neither (no tone map, exposure 1, "
               "no MSAA, supersampling, sky, probes, blending or transmission): the reference for the direct path");
  app.add_flag("--forward-terrain", render.forwardTerrain,
               "Shade the terrain where its patches are drawn, not once a pixel from the surface they leave (the "
               "default without MSAA): the reference for the deferred terrain");
  app.add_flag("--forward-characters", render.forwardCharacters,
               "Shade characters where their triangles are drawn, not once a pixel from the surface they leave "
               "(the default without MSAA): the reference for the deferred characters");
  app.add_option("--terrain-error", render.terrainErrorOverride,
                 "The terrain's LOD target: screen-space error in pixels (default: the scene's terrain.error_pixels)")
      ->check(CLI::Range(0.05, 64.0));
  std::string skinBlend;
  app.add_option("--skin-blend", skinBlend, "Every model's skinning: lbs, dqs or none (the bind pose); default: each model's")
      ->check(CLI::IsMember({"lbs", "dqs", "none"}));
  std::string rotations = "slerp";
  app.add_option("--rotations", rotations, "How the rasterizer interpolates rotation keys: slerp or nlerp (the tracers always slerp)")
      ->check(CLI::IsMember({"slerp", "nlerp"}))->capture_default_str();
  int bookmark = -1;
  app.add_option("--bookmark", bookmark, "Start from camera bookmark N of the scene (out/bookmarks/SCENE.json, saved from the trade panel)")
      ->check(CLI::Range(0, 1000000));
  std::vector<std::string> panelSet;
  app.add_option("--panel-set", panelSet,
                 "Window: the trade panel turns knob KNOB=VALUE on its first frame, as its combo would (msaa=4, "
                 "ambient=sh, skinning=compute, ...); repeatable");
  bool noTimings = false;
  auto* noTimingsFlag =
      app.add_flag("--panel-no-timings", noTimings, "Window: the trade panel shows no timing figures (reproducible screenshots)");
  bool noPanel = false;
  app.add_flag("--no-panel", noPanel,
               "Window: no trade panel, only the frame (what a game shows; a window's frame time without the UI)")
      ->excludes(noTimingsFlag)
      ->excludes("--panel-set");
  app.add_flag("--describe", describe,
               "Print the passes and shader variants built for the scene (--mode raytrace|pathtrace: the scene as "
               "traced and, with --device gpu, the kernel's variant and the buffers it uploads)");
  std::string reference = "off";
  app.add_option("--reference", reference,
                 "Window: the trade panel's reference view at start (off, split, reference or heatmap); it traces "
                 "once the camera holds still with time paused or nothing moving")
      ->check(CLI::IsMember({"off", "split", "reference", "heatmap"}))->capture_default_str();
  double soakSeconds = 0.0, soakReload = 10.0;
  app.add_option("--soak", soakSeconds,
                 "Soak: draw for SECONDS of wall time, the camera circling, the scene reloaded every --soak-reload")
      ->check(CLI::Range(1.0, 1e6));
  app.add_option("--soak-reload", soakReload, "Soak: seconds between reloads of the scene")
      ->check(CLI::Range(0.1, 1e6))->capture_default_str();
  std::string mode = "raster";
  RaytraceOptions rt;
  app.add_option("--mode", mode,
                 "raster (OpenGL), raytrace (the course's Whitted tracer) or pathtrace (the physically based ground truth)")
      ->check(CLI::IsMember({"raster", "raytrace", "pathtrace"}))->capture_default_str();
  app.add_option("--spp", rt.settings.samplesPerPixel, "Ray tracing: stratified samples per pixel")
      ->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--shadow-samples", rt.settings.shadowSamples, "Ray tracing: N x N shadow rays per area light")
      ->check(CLI::Range(1, 64))->capture_default_str();
  auto* maxDepth = app.add_option("--max-depth", rt.settings.maxDepth,
                                  "Ray tracing: bounces after the first hit (raytrace: mirror recursion; pathtrace: "
                                  "0 is direct light only; default 5, pathtrace 16)")
                       ->check(CLI::Range(0, 64));
  app.add_option("--medium-scatterings", rt.settings.mediumScatterings,
                 "Path tracing: scatterings in media a path may take (1: single scattering; default: any)")
      ->check(CLI::Range(0, 1000000));
  app.add_option("--threads", rt.settings.threads, "Ray tracing: worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  app.add_option("--seed", rt.settings.seed, "Ray tracing: random seed")->capture_default_str();
  app.add_option("--rt-precision", rt.precision, "Ray tracing: float or double")
      ->check(CLI::IsMember({"float", "double"}))->capture_default_str();
  app.add_option("--device", rt.device,
                 "Ray tracing: cpu, or gpu (raytrace and pathtrace: the Whitted tracer or the path tracer in a "
                 "compute shader, through the --offscreen backend or in a window)")
      ->check(CLI::IsMember({"cpu", "gpu"}))->capture_default_str();
  app.add_flag("--animate", rt.animate,
               "Ray tracing, --device gpu: trace the scene as it moves, each pass posed at its frame's time (the "
               "characters' BVHs refitted on the GPU); offscreen, a whole image a frame for --frames frames");
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;

  if (options.checkDisplay) return engine::displayAvailable() ? 0 : 1;
  const bool offscreen = !options.offscreen.empty() || describe;
  if (offscreen && options.run.screenshot.empty() && !describe) {
    std::filesystem::create_directories("out");
    options.run.screenshot = "out/demo.png";
  }
  if (describe && options.offscreen.empty()) options.offscreen = "egl";
  if (auto s = engine::finishCommonOptions(options, argc, argv); !s) return fail(engine::kExitBadInput, s.error().message);
  if (scenePath.empty()) scenePath = options.assetDir + "/scenes/demo.json";

  auto scene = engine::loadSceneFile(scenePath);
  if (!scene) return fail(engine::kExitBadInput, scene.error().message);
  // The scene renderer multisamples its own HDR target; the runner's target then
  // only receives the tone-mapped result.
  render.shaderDir = options.shaderDir;
  if (!ambient.empty()) render.ambientOverride = engine::ambientNames().at(ambient);
  if (!skinning.empty()) render.skinningOverride = engine::skinningNames().at(skinning);
  if (lodPixels >= 0.0) render.lodPixelsOverride = lodPixels;
  if (!gpuCulling.empty()) render.gpuCullingOverride = gpuCulling == "on";
  if (!skinBlend.empty()) {
    render.skinModeOverride = skinBlend == "dqs"    ? engine::SkinMode::DualQuat
                              : skinBlend == "none" ? engine::SkinMode::None
                                                    : engine::SkinMode::Linear;
  }
  render.rotations = rotations == "nlerp" ? engine::QuatInterpolation::Nlerp : engine::QuatInterpolation::Slerp;
  render.msaaOverride = options.msaaGiven ? options.run.msaa : 0;
  // A float screenshot is the HDR target read back: direct output has none.
  if (engine::floatFormatForName(options.run.screenshot)) render.hdrTarget = true;
  options.run.targetSamples = 1;
  if (rt.animate && mode == "raster") {
    return fail(engine::kExitBadInput, "--animate: only with --mode raytrace or pathtrace (the rasterizer always animates)");
  }
  if (mode == "raytrace" || mode == "pathtrace") {
    // The tracers select the terrain as the rasterizer does (scene/terrain_mesh.h),
    // from the scene's LOD target: the override becomes it.
    if (render.terrainErrorOverride > 0.0) scene->terrain.errorPixels = render.terrainErrorOverride;
    if (mode == "pathtrace") {
      rt.settings.method = engine::rt::Method::Path;
      // Blender's Cycles default too; Russian roulette makes the deep bounces cheap.
      if (maxDepth->count() == 0) rt.settings.maxDepth = 16;
    }
    rt.settings.width = options.run.width;
    rt.settings.height = options.run.height;
    rt.settings.precision = rt.precision == "double" ? engine::rt::Precision::Double : engine::rt::Precision::Float;
    const bool gpu = rt.device == "gpu";
    if (describe) return describeRaytrace(*scene, options, rt.settings, gpu);
    if (rt.animate && !gpu) return fail(engine::kExitBadInput, "--animate: only with --device gpu");
    if (offscreen && rt.animate) {
      demo::GpuTraceGame game(std::move(scene).value(), options.run.time.value_or(0.0), rt.settings, options.shaderDir,
                              true, true);
      if (auto s = engine::runHeadless(engine::chosenBackend(options), game, options.run); !s)
        return fail(engine::kExitBadInput, s.error().message);
      std::printf("%s\n", options.run.screenshot.c_str());
      return 0;
    }
    if (offscreen) return runRaytraceOffscreen(*scene, options, rt.settings, gpu);
    if (!engine::displayAvailable()) return fail(engine::kExitBadInput, "no usable display; use --offscreen to render to a PNG");
    std::unique_ptr<engine::Game> game;
    if (gpu) {
      game = std::make_unique<demo::GpuTraceGame>(std::move(scene).value(), options.run.time.value_or(0.0), rt.settings,
                                                  options.shaderDir, rt.animate);
    } else {
      game = std::make_unique<demo::RaytraceGame>(std::move(scene).value(), options.run.time.value_or(0.0), rt.settings);
    }
    if (auto status = engine::runWindow(*game, options.run); !status) return fail(engine::kExitBadInput, status.error().message);
    if (!options.run.screenshot.empty()) std::printf("%s\n", options.run.screenshot.c_str());
    return 0;
  }
  const engine::Backend backend = engine::chosenBackend(options);
  if (backend == engine::Backend::Window && !engine::displayAvailable()) {
    return fail(engine::kExitBadInput, "no usable display; use --offscreen to render to a PNG");
  }
  if (soakSeconds > 0.0) return runSoak(scenePath, render, soakSeconds, soakReload, backend, options.run);
  // The trade panel only in a window: offscreen frames never show it.
  demo::SceneGame game(std::move(scene).value(), render, backend == engine::Backend::Window && !noPanel);
  if (bookmark >= 0) game.startAtBookmark(bookmark);
  game.showTimings(!noTimings);
  if (!panelSet.empty()) {
    engine::SceneRenderOptions checked = render;
    for (const std::string& k : panelSet)
      if (auto s = demo::SceneGame::parseKnob(k, checked); !s) return fail(engine::kExitBadInput, s.error().message);
    game.queueKnobs(panelSet);
  }
  const std::map<std::string, demo::ReferenceMode> referenceModes = {{"off", demo::ReferenceMode::Off},
      {"split", demo::ReferenceMode::Split}, {"reference", demo::ReferenceMode::Reference},
      {"heatmap", demo::ReferenceMode::Heatmap}};
  if (backend == engine::Backend::Window) game.reference().mode = referenceModes.at(reference);
  if (describe) {
    // Builds the renderer for the scene (one frame) and prints what it made.
    options.run.frames = 1;
    options.run.screenshot.clear();
    engine::Image ignored;
    const auto status = engine::runHeadless(backend, game, options.run, &ignored, [&game] {
      std::fputs(game.renderer()->describe().c_str(), stdout);
    });
    if (!status) return fail(engine::kExitBadInput, status.error().message);
    return 0;
  }
  const auto status = backend == engine::Backend::Window ? engine::runWindow(game, options.run)
                                                         : engine::runHeadless(backend, game, options.run);
  if (!status) return fail(engine::kExitBadInput, status.error().message);
  if (!options.run.screenshot.empty()) std::printf("%s\n", options.run.screenshot.c_str());
  return 0;
}
