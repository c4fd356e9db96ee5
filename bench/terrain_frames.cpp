// bench/terrain_frames: the terrain's speed against accuracy, per screen-space error
// target. For each target it renders a 4 km field (1 m spacing, the micro_bench
// LOD table's field and camera) through the real scene renderer (sky, sun shadow
// map with the terrain casting, terrain, fog, post) offscreen with EGL, and prints a
// Markdown table: patches and triangles drawn, the largest stated geometric error,
// the largest screen-space error measured against the full-resolution grid, and
// the median and 90th-percentile frame time (render + glFinish), frames of all
// targets interleaved, after warm-up frames (in which each renderer also measures the
// terrain's block errors for the view).
//   build/bin/terrain_frames [--frames N] [--size WxH] [--targets P,P,...] [--shadows on|off]
//                            [--backend egl|osmesa]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "asset/scene_desc.h"
#include "gl/resources.h"
#include "platform/gl_context.h"
#include "render/camera.h"
#include "render/scene_renderer.h"
#include "terrain/lod.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain.h"
#include "terrain_error.h"

using namespace engine;

namespace {

struct Options {
  int frames = 15;
  int width = 1280, height = 720;
  Backend backend = Backend::Egl;
  std::vector<double> targets{0.5, 1.0, 2.0, 4.0, 8.0};
  bool shadows = true;
  std::string command;
};

[[noreturn]] void usage(const char* message) {
  std::fprintf(stderr, "terrain_frames: %s\nusage: terrain_frames [--frames N] [--size WxH] [--targets P,P,...] [--shadows on|off] [--backend egl|osmesa]\n",
               message);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  o.command = "build/bin/terrain_frames";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    o.command += " " + a;
    if (i + 1 >= argc) usage(("missing value after " + a).c_str());
    const std::string v = argv[++i];
    o.command += " " + v;
    if (a == "--frames") {
      o.frames = std::atoi(v.c_str());
      if (o.frames < 1) usage("--frames: at least 1");
    } else if (a == "--size") {
      if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16)
        usage("--size: WxH, at least 16x16");
    } else if (a == "--targets") {
      o.targets.clear();
      for (std::size_t at = 0; at < v.size();) {
        const std::size_t comma = std::min(v.find(',', at), v.size());
        const double t = std::atof(v.substr(at, comma - at).c_str());
        if (!(t > 0.0)) usage("--targets: comma-separated pixels, each > 0");
        o.targets.push_back(t);
        at = comma + 1;
      }
    } else if (a == "--shadows") {
      if (v != "on" && v != "off") usage("--shadows: on or off");
      o.shadows = v == "on";
    } else if (a == "--backend") {
      const auto b = parseBackend(v);
      if (!b || *b == Backend::Window) usage("--backend: egl or osmesa");
      o.backend = *b;
    } else {
      usage(("unknown option " + a).c_str());
    }
  }
  return o;
}

// The micro_bench table's field (bench/micro/terrain_bench.cpp, terrainOf(4096)).
SceneDesc sceneFor(double errorPixels, bool shadows) {
  SceneDesc scene;
  scene.path = "terrain_frames";
  scene.terrain.enabled = true;
  scene.terrain.seed = 7;
  scene.terrain.size = 4096.0;
  scene.terrain.spacing = 1.0;
  scene.terrain.heightScale = 600.0;
  scene.terrain.origin = {2.0e6, 0.0, -5.0e6};
  scene.terrain.errorPixels = errorPixels;
  LightDesc sun;
  sun.direction = glm::normalize(glm::dvec3(-0.6, 0.5, -0.3));
  sun.color = {1.0f, 0.93f, 0.85f};
  sun.intensity = 2.6f;
  sun.shadows = shadows;
  scene.lights.push_back(sun);
  scene.fog.enabled = true;
  scene.fog.density = 0.0006f;
  return scene;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::size_t(q * double(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  ContextOptions contextOptions;
  contextOptions.width = options.width;
  contextOptions.height = options.height;
  auto context = createContext(options.backend, contextOptions);
  if (!context) {
    std::fprintf(stderr, "terrain_frames: %s\n", context.error().message.c_str());
    return 1;
  }
  const SceneDesc base = sceneFor(1.0, options.shadows);
  auto field = terrain::Terrain::create(terrain::settingsFromScene(base.terrain));
  if (!field) {
    std::fprintf(stderr, "terrain_frames: %s\n", field.error().message.c_str());
    return 1;
  }
  // The micro_bench camera: 30 m above the ground at (600, 800), looking along
  // the valley and a little down.
  const glm::dvec3 o = base.terrain.origin;
  Camera camera;
  camera.position = {o.x + 600.0, field->heightAt(o.x + 600.0, o.z + 800.0) + 30.0, o.z + 800.0};
  camera.nearPlane = 0.5;
  camera.farPlane = 100000.0;
  camera.lookAt(camera.position + glm::dvec3(1.0, -0.12, 0.7));

  gl::Texture color = gl::Texture::create2D(GL_RGBA8, options.width, options.height, 1);
  gl::Framebuffer target = gl::Framebuffer::create();
  target.attach(GL_COLOR_ATTACHMENT0, color);
  if (auto s = target.check("terrain_frames target"); !s) {
    std::fprintf(stderr, "terrain_frames: %s\n", s.error().message.c_str());
    return 1;
  }

  std::printf("| target (px) | patches | triangles | max geometric error (m) | max screen error (px) | frame median (ms) | frame p90 (ms) |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  // One renderer per target, all alive, frames taken round-robin: load from other
  // work on the machine then falls on every target alike, and the ratios hold.
  std::vector<std::unique_ptr<SceneRenderer>> renderers;
  for (double pixels : options.targets) {
    SceneDesc scene = sceneFor(pixels, options.shadows);
    scene.camera.position = camera.position;
    scene.camera.forward = camera.forward();
    scene.camera.nearPlane = camera.nearPlane;
    scene.camera.farPlane = camera.farPlane;
    SceneRenderOptions renderOptions;
    renderOptions.shaderDir = ENGINE_SOURCE_DIR "/shaders";
    auto renderer = SceneRenderer::create(scene, renderOptions);
    if (!renderer) {
      std::fprintf(stderr, "terrain_frames: %s\n", renderer.error().message.c_str());
      return 1;
    }
    renderers.push_back(std::move(renderer).value());
  }
  target.bind();
  std::vector<std::vector<double>> ms(renderers.size());
  // Two rounds to warm up: pages, shaders, and the terrain's block errors, which each
  // renderer measures on its first frame of the view.
  for (int i = -2; i < options.frames; ++i) {
    for (std::size_t r = 0; r < renderers.size(); ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      if (auto s = renderers[r]->render(camera, options.width, options.height); !s) {
        std::fprintf(stderr, "terrain_frames: %s\n", s.error().message.c_str());
        return 1;
      }
      glFinish();
      const auto t1 = std::chrono::steady_clock::now();
      if (i >= 0) ms[r].push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
  }

  for (std::size_t r = 0; r < renderers.size(); ++r) {
    const double pixels = options.targets[r];
    // The same selection the renderer made (same camera, viewport and culling
    // matrix: reverse-Z projection times the view rotation), for the errors.
    terrain::LodCamera lod;
    lod.position = camera.position;
    lod.fovY = glm::radians(camera.fovyDegrees);
    lod.viewportHeight = options.height;
    const double aspect = double(options.width) / options.height;
    lod.viewProjection = glm::mat4(glm::perspectiveRH_ZO(lod.fovY, aspect, camera.farPlane, camera.nearPlane) *
                                   glm::lookAt(glm::dvec3(0.0), camera.forward(), glm::dvec3(0, 1, 0)));
    lod.zeroToOneDepth = true;
    terrain::measureBlocks(*field, lod, pixels);  // as the renderer did
    const terrain::LodSelection selection = terrain::selectLod(*field, lod, pixels);
    const int drawn = renderers[r]->stats().terrainTriangles;
    if (std::size_t(drawn) != selection.stats.triangles)
      std::fprintf(stderr, "terrain_frames: note: the renderer drew %d triangles, the mirror selection has %zu\n",
                   drawn, selection.stats.triangles);
    std::printf("| %.2g | %zu | %d | %.3f | %.3f | %.1f | %.1f |\n", pixels, selection.stats.patches, drawn,
                double(selection.stats.maxGeometricError),
                terrain::bench::measuredScreenError(*field, selection, lod), percentile(ms[r], 0.5),
                percentile(ms[r], 0.9));
  }
  std::printf("\n%s, %dx%d, sun shadows %s, %d frames per target taken round-robin after 2 warm-up rounds; "
              "command: %s\n",
              (*context)->renderer().c_str(), options.width, options.height, options.shadows ? "on" : "off",
              options.frames, options.command.c_str());
  return 0;
}
