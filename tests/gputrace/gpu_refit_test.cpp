// Characters refitted on the GPU (gputrace/gpu_refit.h), through EGL and OSMesa: a
// group's vertices moved, refitted in the tracer's own buffers by rt/refit.comp, must
// be the CPU's refit flattened again, byte for byte (leaves, triangle normals, every
// node's boxes, the instance's bounds), in both node layouts; and the tracer then
// finds the CPU's hits in the moved scene.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "../support/gl_test.h"
#include "../support/rt_queries.h"
#include "../support/rt_textured.h"
#include "asset/scene_file.h"
#include "gputrace/gpu_poses.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/scene_builder.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// Group 0 the static grid; group 1 a grid with normals and a soup (what moves);
// group 2 empty; group 3 another soup. Group 1's mesh ids come back in `moving`.
rt::RtScene sceneWithCharacters(std::vector<rt::MeshId>& moving) {
  std::mt19937 rng(23);
  rt::RtScene scene;
  (void)scene.addMesh(test::gridMesh(7.0f, 0));
  const int character = scene.addGroup();
  for (rt::RtMesh mesh : {test::gridMesh(2.0f, character), test::soupMesh(700, rng, character)}) {
    const auto id = scene.addMesh(std::move(mesh));
    EXPECT_TRUE(id) << id.error().message;
    moving.push_back(id.value());
  }
  scene.addGroup();
  (void)scene.addMesh(test::soupMesh(300, rng, scene.addGroup()));
  scene.build();
  return scene;
}

// The moving meshes' new vertices (as skinning would move them: a bend and some
// jitter, normals turned with it), applied to the CPU scene and packed as the GPU
// refit reads them: position and normal, two vec4 a vertex, meshes in order.
std::vector<glm::vec4> moveMeshes(rt::RtScene& scene, const std::vector<rt::MeshId>& moving, std::uint32_t seed,
                                  double& cpuRefitSeconds) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> jitter(0.0f, 0.05f);
  std::vector<glm::vec4> packed;
  for (const rt::MeshId id : moving) {
    const rt::RtMesh& mesh = scene.meshes()[std::size_t(id)];
    std::vector<glm::vec3> positions, normals;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 p = mesh.positions[v];
      const float bend = 0.3f * std::sin(0.4f * p.x);
      positions.push_back(p + glm::vec3(jitter(rng), jitter(rng), bend + jitter(rng)));
      if (!mesh.normals.empty()) normals.push_back(glm::normalize(mesh.normals[v] + glm::vec3(0.12f * std::cos(0.4f * p.x), 0.0f, 0.0f)));
      packed.emplace_back(positions.back(), 1.0f);
      packed.emplace_back(normals.empty() ? glm::vec3(0.0f) : normals.back(), 0.0f);
    }
    EXPECT_TRUE(scene.updateMesh(id, positions, normals));
  }
  cpuRefitSeconds = scene.refit();
  return packed;
}

template <typename T>
bool sameBytes(GLuint buffer, const std::vector<T>& expected) {
  std::vector<T> actual(expected.size());
  glGetNamedBufferSubData(buffer, 0, GLsizeiptr(expected.size() * sizeof(T)), actual.data());
  return expected.empty() || std::memcmp(actual.data(), expected.data(), expected.size() * sizeof(T)) == 0;
}

class GpuRefitting : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuRefitting);

TEST_P(GpuRefitting, EqualsTheCpusRefitByteForByte) {
  for (const int width : {8, 4}) {
    SCOPED_TRACE(width);
    std::vector<rt::MeshId> moving;
    rt::RtScene scene = sceneWithCharacters(moving);
    auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir(), width);
    ASSERT_TRUE(tracer) << tracer.error().message;
    auto refit = gpurt::GpuRefit::create(scene, tracer->layout(), 1, test::shaderDir());
    ASSERT_TRUE(refit) << refit.error().message;
    double cpuSeconds = 0.0;
    const std::vector<glm::vec4> vertices = moveMeshes(scene, moving, 5, cpuSeconds);
    ASSERT_EQ(vertices.size(), 2 * std::size_t(refit->vertexCount()));
    const gl::Buffer input = gl::Buffer::create(vertices.size() * sizeof(glm::vec4), vertices.data());
    refit->run(input, 2, tracer->buffers());  // the first run compiles the kernel (llvmpipe: at first use)
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    refit->run(input, 2, tracer->buffers());
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    const rt::GpuSceneLayout expected = rt::flattenScene(scene, width);
    const gpurt::GpuRefit::Targets b = tracer->buffers();
    EXPECT_TRUE(width == 4 ? sameBytes(b.nodes, expected.nodes4) : sameBytes(b.nodes, expected.nodes)) << "node boxes";
    EXPECT_TRUE(sameBytes(b.leaves, expected.leaves)) << "leaf positions";
    EXPECT_TRUE(sameBytes(b.triangles, expected.triangles)) << "triangle normals";
    EXPECT_TRUE(sameBytes(b.instances, expected.instances)) << "instance bounds";
    // The refit changed something: the boxes before the move are not these.
    EXPECT_NE(std::memcmp(tracer->layout().leaves.data(), expected.leaves.data(), expected.leaves.size() * sizeof(rt::GpuLeaf)), 0);

    // Traced after the refit: the moved scene's hits.
    const std::vector<rt::Ray<float>> rays = test::queryRays(3000, 7.0f, 4);
    std::vector<gpurt::RayQuery> queries;
    for (const auto& r : rays) queries.push_back(gpurt::RayQuery{glm::vec4(r.o, r.tMax), glm::vec4(r.d, 0.0f)});
    const std::vector<gpurt::RayAnswer> answers = tracer->trace(queries);
    int mismatches = 0, hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const auto cpu = scene.intersect(rays[i]);
      hits += cpu ? 1 : 0;
      const bool gpuHit = answers[i].kind != gpurt::HitKind::None;
      // 1e-5 relative: the GPU's own division and square root (GpuTrace.* says why).
      if (gpuHit != cpu.has_value() || (cpu && std::abs(answers[i].t - cpu->t) > 1e-5f * cpu->t)) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0) << "of " << rays.size();
    EXPECT_GT(hits, int(rays.size()) / 2);
    std::printf("gpu refit, %d wide: %u vertices, %zu levels of nodes, %.2f ms (the CPU's refit %.2f ms); %d of %zu rays hit after it\n",
                width, refit->vertexCount(), rt::refitPlan(scene, tracer->layout(), 1).levels.size(), ms, 1e3 * cpuSeconds,
                hits, rays.size());
  }
}

// Two of the shipped character on a floor, walking (LBS) and waving (DQS), as
// AnimatedRtScene builds a scene file's models: each its own BVH group.
std::filesystem::path charactersScene() {
  const std::filesystem::path file = test::temporaryFile("gpu_poses.json");
  std::ofstream(file) << R"({
  "camera": {"position": [0.4, 1.3, 3.4], "target": [0.0, 0.9, 0.0], "fovy": 45},
  "lights": [{"type": "sun", "direction": [-0.4, 0.8, 0.5], "intensity": 2.0, "shadows": true},
             {"type": "point", "position": [1.5, 2.5, 2.0], "intensity": 3.0}],
  "materials": {"floor": {"color": [0.6, 0.6, 0.55], "roughness": 0.8}},
  "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "extent": 6, "material": "floor"}],
  "models": [
    {"path": ")" + std::string(ENGINE_SOURCE_DIR) + R"(/assets/models/character.gltf", "position": [-0.5, 0, 0], "clip": "Walk"},
    {"path": ")" + std::string(ENGINE_SOURCE_DIR) + R"(/assets/models/character.gltf", "position": [0.6, 0, -0.3], "clip": "Wave", "skinning": "dqs"}
  ],
  "render": {"shading": "pbr"}
})";
  return file;
}

// GpuPoses: the scene posed again (AnimatedRtScene::setTime), its characters'
// vertices uploaded and their groups refitted on the GPU, traces the very image a
// tracer made from scratch of the posed scene does (Whitted, 96 x 54, the same bits
// and ray counts), and not the image of the pose before.
TEST_P(GpuRefitting, APosedSceneTracesAsATracerMadeFromIt) {
  const std::filesystem::path file = charactersScene();
  auto desc = loadSceneFile(file.string());
  std::filesystem::remove(file);
  ASSERT_TRUE(desc) << desc.error().message;
  rt::RenderSettings settings;
  settings.width = 96;
  settings.height = 54;
  auto animated = rt::AnimatedRtScene::create(*desc, 0.2, settings.height);
  ASSERT_TRUE(animated) << animated.error().message;
  ASSERT_EQ(animated->instanceCount(), 2u);
  auto tracer = gpurt::GpuTracer::create(animated->scene(), test::shaderDir());
  ASSERT_TRUE(tracer) << tracer.error().message;
  auto poses = gpurt::GpuPoses::create(*animated, *tracer, test::shaderDir());
  ASSERT_TRUE(poses) << poses.error().message;
  auto before = tracer->render(settings);
  ASSERT_TRUE(before) << before.error().message;

  ASSERT_TRUE(animated->setTime(1.3));
  poses->update(*animated, *tracer);  // the first run compiles the refit kernel (llvmpipe: at first use)
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  poses->update(*animated, *tracer);
  glFinish();
  const double updateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  auto refitted = tracer->render(settings);
  ASSERT_TRUE(refitted) << refitted.error().message;
  const auto freshStart = std::chrono::steady_clock::now();
  auto fresh = gpurt::GpuTracer::create(animated->scene(), test::shaderDir());
  ASSERT_TRUE(fresh) << fresh.error().message;
  glFinish();
  const double freshMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - freshStart).count();
  auto expected = fresh->render(settings);
  ASSERT_TRUE(expected) << expected.error().message;

  int differing = 0, moved = 0;
  for (std::size_t i = 0; i < expected->image.pixels.size(); ++i) {
    differing += refitted->image.pixels[i] != expected->image.pixels[i] ? 1 : 0;
    moved += before->image.pixels[i] != expected->image.pixels[i] ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(refitted->rays.shadow, expected->rays.shadow);
  EXPECT_GT(moved, 100) << "the characters should have moved";
  EXPECT_GT(poses->vertices(), 1000u);
  std::printf("gpu poses: %zu vertices refitted in %.2f ms (a new tracer of the posed scene: %.1f ms), %d of %zu pixels "
              "moved, %d differ from the new tracer's\n",
              poses->vertices(), updateMs, freshMs, moved, expected->image.pixels.size(), differing);
}

}  // namespace
