// raster_floor: what the scene renderer costs above the simplest possible GL loop.
//
//   raster_floor [SCENE.json] [--offscreen egl|osmesa] [--size WxH] [--time T] [--frames N]
//
// The floor draws the same triangles the scene shows at time T (characters skinned on
// the CPU, the terrain's CDLOD selection for this camera less what its opaque planes
// hide (as the renderer leaves it out), boxes, spheres and planes
// tessellated as the rasterizer does) with one program, one vertex array and one draw
// call per frame, no shadows, no post pass. Frames of the real renderer and of the
// floor alternate in one process, so both see the same machine load; the table gives
// medians, p95, the ratio of medians, and the work counters of one frame of each.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <glm/gtc/matrix_transform.hpp>

#include "app/cli.h"
#include "app/frame_stats.h"
#include "app/runner_common.h"
#include "asset/scene_file.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "raytrace/scene_builder.h"
#include "render/mesh.h"
#include "terrain/lod.h"
#include "terrain/page_cache.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain.h"
#include "render/render_target.h"
#include "render/terrain_cull.h"
#include "render/scene_renderer.h"

namespace {

// Appends `shape` placed by `world`, camera-relative (the offset taken in double).
void appendShape(engine::ShapeData& out, const engine::ShapeData& shape, const glm::dmat4& world,
                 const glm::dvec3& eye) {
  const auto base = static_cast<std::uint32_t>(out.vertices.size());
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
  for (const engine::Vertex& v : shape.vertices) {
    const glm::dvec3 p = glm::dvec3(world * glm::dvec4(glm::dvec3(v.position), 1.0)) - eye;
    out.vertices.push_back({glm::vec3(p), glm::vec3(glm::normalize(normalMatrix * glm::dvec3(v.normal))), v.uv});
  }
  for (std::uint32_t i : shape.indices) out.indices.push_back(base + i);
}

// The terrain patches the rasterizer draws from this camera (its CDLOD selection,
// culled to the view, less what its opaque planes hide), camera-relative as
// patchVertices gives them.
engine::Status appendTerrain(engine::ShapeData& out, const engine::SceneDesc& scene, const glm::dmat4& viewProjection,
                             glm::ivec2 size) {
  auto field = engine::terrain::Terrain::create(engine::terrain::settingsFromScene(scene.terrain));
  if (!field) return engine::makeError(scene.path + ": /terrain: " + field.error().message);
  engine::terrain::LodCamera camera;
  camera.position = scene.camera.position;
  camera.viewProjection = glm::mat4(viewProjection);
  camera.fovY = glm::radians(scene.camera.fovyDegrees);
  camera.viewportHeight = size.y;
  // The block errors the view needs, as the renderer measures them.
  engine::terrain::measureBlocks(*field, camera, scene.terrain.errorPixels);
  auto selection = engine::terrain::selectLod(*field, camera, scene.terrain.errorPixels);
  const auto planes = engine::cull::opaquePlanes(scene, scene.camera.position, viewProjection, glm::dvec2(size));
  engine::removeHiddenPatches(*field, selection, planes, viewProjection, glm::dvec2(size));
  const std::vector<std::uint32_t> indices = engine::terrain::patchIndices();
  for (const auto& patch : selection.patches) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (const glm::vec3& v : engine::terrain::patchVertices(*field, selection, patch)) {
      out.vertices.push_back({v, glm::vec3(0, 1, 0), {}});
    }
    for (std::uint32_t i : indices) out.indices.push_back(base + i);
  }
  return engine::Ok{};
}

// The scene's triangles at `time` as the rasterizer draws them: the characters
// skinned on the CPU with the same jobs (the ray tracer's scene builder), kept when
// their box meets the view as the rasterizer culls them; the terrain's selection;
// analytic shapes tessellated as the rasterizer does.
engine::Result<engine::ShapeData> floorGeometry(const engine::SceneDesc& scene, double time, glm::ivec2 size,
                                                const glm::dmat4& viewProjection) {
  engine::SceneDesc withoutTerrain = scene;
  withoutTerrain.terrain.enabled = false;
  auto rt = engine::rt::buildRtScene(withoutTerrain, time, size.y);
  if (!rt) return rt.error();
  const glm::dvec3 eye = scene.camera.position;
  const auto frustum = engine::terrain::Frustum::fromViewProjection(glm::mat4(viewProjection));
  engine::ShapeData out;
  for (const engine::rt::RtMesh& mesh : rt->meshes()) {
    engine::ShapeData shape;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      shape.vertices.push_back({mesh.positions[i], mesh.normals.empty() ? glm::vec3(0, 1, 0) : mesh.normals[i], {}});
      lo = glm::min(lo, glm::dvec3(mesh.positions[i]) - eye);
      hi = glm::max(hi, glm::dvec3(mesh.positions[i]) - eye);
    }
    if (!frustum.intersects(lo, hi)) continue;
    shape.indices = mesh.indices;
    appendShape(out, shape, glm::dmat4(1.0), eye);
  }
  for (const engine::PrimitiveDesc& p : scene.primitives) {
    if (p.type == engine::PrimitiveType::Box) continue;  // already a mesh of the ray tracer's
    appendShape(out, engine::shapeForPrimitive(p), engine::primitiveTransform(p, scene.camera.farPlane), eye);
  }
  if (scene.terrain.enabled) {
    if (auto s = appendTerrain(out, scene, viewProjection, size); !s) return s.error();
  }
  return out;
}

glm::dmat4 viewProjectionOf(const engine::CameraDesc& c, double aspect) {
  return glm::perspective(glm::radians(c.fovyDegrees), aspect, c.nearPlane, c.farPlane) *
         glm::lookAt(glm::dvec3(0.0), c.forward, c.up);
}

// The floor: one program, one vertex array, one draw call.
class Floor {
 public:
  engine::Status init(const engine::ShapeData& geometry, const std::string& shaderDir) {
    auto program = engine::gl::Program::build(
        shaderDir, {{GL_VERTEX_SHADER, "floor.vert"}, {GL_FRAGMENT_SHADER, "floor.frag"}});
    if (!program) return program.error();
    program_ = std::move(program).value();
    mesh_ = std::make_unique<engine::GpuMesh>(geometry);
    return engine::Ok{};
  }
  void setViewProjection(const glm::dmat4& viewProjection) { viewProjection_ = viewProjection; }
  void draw() const {
    glClearColor(0.5f, 0.6f, 0.7f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // planes are seen from both sides
    program_.use();
    program_.set("u_viewProjection", glm::mat4(viewProjection_));
    program_.set("u_sunDirection", glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    mesh_->draw();
  }
  long long triangles() const { return mesh_->indexCount() / 3; }

 private:
  engine::gl::Program program_;
  std::unique_ptr<engine::GpuMesh> mesh_;
  glm::dmat4 viewProjection_{1.0};
};

double timeFrame(const engine::RenderTarget& target, const std::function<void()>& draw) {
  const auto start = std::chrono::steady_clock::now();
  target.bind();
  draw();
  target.resolve();
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int fail(const std::string& message) {
  std::fprintf(stderr, "raster_floor: %s\n", message.c_str());
  return engine::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Times the scene renderer against the simplest GL loop drawing the same triangles.", "raster_floor"};
  engine::CommonOptions options;
  std::string scenePath;
  app.add_option("scene", scenePath, "Scene file (JSON); default: assets/scenes/demo.json");
  engine::addCommonOptions(app, options);
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;
  if (options.offscreen.empty()) options.offscreen = "egl";
  if (!options.frames) options.frames = 30;
  if (auto s = engine::finishCommonOptions(options, argc, argv); !s) return fail(s.error().message);
  if (scenePath.empty()) scenePath = options.assetDir + "/scenes/demo.json";
  auto scene = engine::loadSceneFile(scenePath);
  if (!scene) return fail(scene.error().message);
  const double time = options.run.time.value_or(0.0);
  const int width = options.run.width, height = options.run.height;

  engine::keepFreedMemory();
  engine::ContextOptions contextOptions;
  contextOptions.width = width;
  contextOptions.height = height;
  auto context = engine::createContext(engine::chosenBackend(options), contextOptions);
  if (!context) return fail(context.error().message);
  auto target = engine::RenderTarget::create(width, height, 1);
  if (!target) return fail(target.error().message);

  engine::SceneRenderOptions renderOptions;
  renderOptions.shaderDir = options.shaderDir;
  auto renderer = engine::SceneRenderer::create(*scene, renderOptions);
  if (!renderer) return fail(renderer.error().message);
  const engine::Camera camera = (*renderer)->initialCamera();
  const glm::dmat4 viewProjection = viewProjectionOf(scene->camera, double(width) / double(height));
  auto geometry = floorGeometry(*scene, time, {width, height}, viewProjection);
  if (!geometry) return fail(geometry.error().message);
  Floor floor;
  if (auto s = floor.init(*geometry, options.shaderDir); !s) return fail(s.error().message);
  floor.setViewProjection(viewProjection);

  std::vector<double> sceneMs, floorMs;
  engine::Status frame = engine::Ok{};
  for (int i = 0; i < options.run.frames && frame; ++i) {
    sceneMs.push_back(timeFrame(*target, [&] {
      frame = (*renderer)->update(time);
      if (frame) frame = (*renderer)->render(camera, width, height);
    }));
    floorMs.push_back(timeFrame(*target, [&] { floor.draw(); }));
  }
  if (!frame) return fail(frame.error().message);
  const engine::FrameSummary real = engine::summarize(sceneMs), bare = engine::summarize(floorMs);
  const engine::SceneStats& stats = (*renderer)->stats();
  std::printf("%s at %dx%d, t = %g s, %s, %d frames each, alternating\n\n", scenePath.c_str(), width, height, time,
              std::string(engine::backendName((*context)->backend())).c_str(), options.run.frames);
  std::printf("| loop | median ms | p95 ms | draw calls | program changes | triangles (all passes) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::printf("| scene renderer | %.1f | %.1f | %d | %d | %lld |\n", real.medianMs, real.p95Ms, stats.drawCalls,
              stats.programChanges, (*renderer)->lastFrameTriangles());
  std::printf("| floor: one program, one draw | %.1f | %.1f | 1 | 1 | %lld |\n", bare.medianMs, bare.p95Ms,
              floor.triangles());
  std::printf("\nratio of medians (scene / floor): %.2f\ncommand: %s\n", real.medianMs / bare.medianMs,
              options.run.command.c_str());
  return 0;
}
