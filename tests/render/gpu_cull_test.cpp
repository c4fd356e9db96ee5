// GPU culling (render/gpu_cull.h) on a real offscreen context, both backends: the
// Hi-Z pyramid's compute and the cull's compute against their CPU twin
// (render/cull_math.h), and a scene drawn with culling on and off: the same bytes,
// with something culled; and with a deliberately non-conservative depth margin,
// not the same bytes (what the golden comparison of tests/golden/gpu_culling_test
// relies on to catch a culling bug).
#include <gtest/gtest.h>

#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/gpu_cull.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

class GpuCull : public GlTest {};

// A framebuffer whose depth texture holds `depth` (w x h, bottom row first).
struct DepthTarget {
  gl::Texture depth;
  gl::Framebuffer fbo;
};
DepthTarget gpuCullDepthTarget(const std::vector<float>& depth, int w, int h) {
  DepthTarget t{gl::Texture::create2D(GL_DEPTH_COMPONENT32F, w, h, 1), gl::Framebuffer::create()};
  glTextureSubImage2D(t.depth.id(), 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  t.fbo.attach(GL_DEPTH_ATTACHMENT, t.depth);
  return t;
}

// Blocky depth: walls at several distances, and gaps of nothing (0: far).
std::vector<float> gpuCullDepth(int w, int h, int seed) {
  std::vector<float> depth(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int cell = ((x / 13) * 7 + (y / 11) * 3 + seed) % 6;
      depth[size_t(y * w + x)] = cell == 5 ? 0.0f : 0.005f + 0.01f * float(cell);
    }
  return depth;
}

glm::mat4 gpuCullViewProjection(float aspect) {
  const glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(50.0f), aspect, 100.0f, 0.05f);
  return projection * glm::lookAt(glm::vec3(0.0f), glm::vec3(0.1f, -0.05f, -1.0f), glm::vec3(0, 1, 0));
}

TEST_P(GpuCull, HiZPyramidEqualsItsCpuTwin) {
  for (auto [w, h] : {std::pair{75, 43}, {64, 64}, {1, 1}, {129, 7}}) {
    const std::vector<float> depth = gpuCullDepth(w, h, w);
    const DepthTarget target = gpuCullDepthTarget(depth, w, h);
    auto pyramid = HiZPyramid::create(test::shaderDir());
    ASSERT_TRUE(pyramid.ok()) << pyramid.error().message;
    pyramid->build(target.fbo.id(), w, h);
    const cull::HiZ gpu = pyramid->read();
    const cull::HiZ cpu = cull::HiZ::build(depth, w, h);
    ASSERT_EQ(gpu.levels.size(), cpu.levels.size());
    for (size_t level = 0; level < cpu.levels.size(); ++level)
      EXPECT_EQ(gpu.levels[level], cpu.levels[level]) << w << "x" << h << " level " << level + 1;
  }
}

// Random jobs over random clusters: instances with and without spheres, instance
// only, instanced, one of 2,500 clusters (three of cull.comp's merge chunks); the commands
// and counters the compute writes are the twin's, against the pyramid and the
// frustum alone.
TEST_P(GpuCull, CullEqualsItsCpuTwin) {
  const int w = 160, h = 90;
  const std::vector<float> depth = gpuCullDepth(w, h, 1);
  const DepthTarget target = gpuCullDepthTarget(depth, w, h);
  auto pyramid = HiZPyramid::create(test::shaderDir());
  ASSERT_TRUE(pyramid.ok()) << pyramid.error().message;
  pyramid->build(target.fbo.id(), w, h);
  const cull::HiZ hiz = cull::HiZ::build(depth, w, h);

  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto culler = GpuCuller::create(test::shaderDir());
  ASSERT_TRUE(culler.ok()) << culler.error().message;
  for (int j = 0; j < 300; ++j) {
    const int clusters = j == 7 ? 2500 : 1 + int(rng() % 40);
    std::vector<cull::Cluster> table;
    for (int c = 0; c < clusters; ++c) {
      const glm::vec3 centre(6.0f * (u(rng) - 0.5f), 6.0f * (u(rng) - 0.5f), 6.0f * (u(rng) - 0.5f));
      const glm::vec3 r = glm::vec3(0.05f) + 0.5f * glm::vec3(u(rng), u(rng), u(rng));
      table.push_back({centre - r, std::uint32_t(384 * c), centre + r, 384});
    }
    table.push_back({glm::vec3(-4.0f), 0, glm::vec3(4.0f), std::uint32_t(384 * clusters)});
    cull::Job job;
    job.firstCluster = culler->addClusters(table);
    job.clusterCount = std::uint32_t(clusters);
    const glm::vec3 at(40.0f * (u(rng) - 0.5f), 20.0f * (u(rng) - 0.5f), -2.0f - 60.0f * u(rng));
    job.model = glm::rotate(glm::translate(glm::mat4(1.0f), at), 6.0f * u(rng), glm::normalize(glm::vec3(u(rng), u(rng), 0.1f)));
    job.sphere = j % 3 == 0 ? glm::vec4(0, 0, 0, -1) : glm::vec4(at, 4.0f * u(rng) + 1.0f);
    // Every fifth instance only, every seventh instanced (the terrain's patches).
    job.flags = j % 5 == 0 ? cull::kInstanceOnly : j % 7 == 0 ? cull::kInstances : 0u;
    job.firstInstance = std::uint32_t(j);
    culler->addJob(job);
  }
  const std::vector<cull::Job> jobs = culler->jobs();  // with their commands assigned
  cull::View view;
  view.viewProjection = gpuCullViewProjection(float(w) / float(h));
  for (const bool occlusion : {true, false}) {
    SCOPED_TRACE(occlusion ? "frustum and hi-z" : "frustum only");
    culler->upload();  // zeroes the counters
    culler->cull(0, jobs.size(), view.viewProjection, occlusion ? &*pyramid : nullptr);
    const std::vector<cull::Command> gpu = culler->commands();
    const cull::Counters gpuCounters = culler->counters();
    view.hiz = occlusion ? &hiz : nullptr;
    std::vector<cull::Command> cpu(gpu.size());
    cull::Counters cpuCounters;
    cullJobs(jobs, culler->clusters(), view, cpu, cpuCounters);
    int differ = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
      const bool same = gpu[i].count == cpu[i].count && gpu[i].instanceCount == cpu[i].instanceCount &&
                        gpu[i].firstIndex == cpu[i].firstIndex && gpu[i].baseVertex == cpu[i].baseVertex &&
                        gpu[i].baseInstance == cpu[i].baseInstance;
      if (!same && differ++ < 5) ADD_FAILURE() << "command " << i << ": gpu count " << gpu[i].count << " x" << gpu[i].instanceCount << ", cpu " << cpu[i].count << " x" << cpu[i].instanceCount;
    }
    EXPECT_EQ(differ, 0);
    EXPECT_EQ(gpuCounters.instancesTested, cpuCounters.instancesTested);
    EXPECT_EQ(gpuCounters.instancesFrustum, cpuCounters.instancesFrustum);
    EXPECT_EQ(gpuCounters.instancesOccluded, cpuCounters.instancesOccluded);
    EXPECT_EQ(gpuCounters.clustersTested, cpuCounters.clustersTested);
    EXPECT_EQ(gpuCounters.clustersFrustum, cpuCounters.clustersFrustum);
    EXPECT_EQ(gpuCounters.clustersOccluded, cpuCounters.clustersOccluded);
    // The case is not empty: every verdict occurs.
    EXPECT_GT(cpuCounters.instancesFrustum, 0u);
    EXPECT_GT(cpuCounters.clustersFrustum, 0u);
    EXPECT_LT(cpuCounters.clustersFrustum + cpuCounters.clustersOccluded, cpuCounters.clustersTested);
    if (occlusion) {
      EXPECT_GT(cpuCounters.instancesOccluded, 0u);
      EXPECT_GT(cpuCounters.clustersOccluded, 0u);
    } else {
      EXPECT_EQ(cpuCounters.instancesOccluded + cpuCounters.clustersOccluded, 0u);
    }
  }
}

// A wall with two balls hidden behind it, a ball in front of it and the robot
// (unskinned: its clusters have bounds) behind it, its head above the wall.
constexpr const char* kCullScene = R"({
  "camera": {"position": [0, 1.3, 0], "target": [0, 1.0, -6], "fovy": 50},
  "lights": [{"type": "sun", "direction": [0.3, 1, 0.5], "intensity": 1.2, "shadows": false}],
  "materials": {"a_wall": {"color": [0.7, 0.7, 0.7]}, "b_hidden": {"color": [1, 0, 0]},
                "c_front": {"color": [0, 0, 1]}},
  "primitives": [
    {"type": "box", "min": [-3, 0, -6.5], "max": [3, 1.3, -6], "material": "a_wall"},
    {"type": "sphere", "center": [-1, 0.6, -9], "radius": 0.5, "material": "b_hidden"},
    {"type": "sphere", "center": [1, 0.5, -10], "radius": 0.5, "material": "b_hidden"},
    {"type": "sphere", "center": [1.2, 0.7, -4.5], "radius": 0.3, "material": "c_front"}
  ],
  "models": [{"path": "../models/character.gltf", "position": [0, 0, -8], "skinning": "none"}],
  "sky": {"enabled": false, "background": [0.2, 0.3, 0.4]},
  "render": {"shading": "classic", "tonemap": "none"}
})";

struct CulledFrame {
  Image image;
  CullStats stats;
};

CulledFrame renderCullScene(bool culling, float depthMargin = cull::kDepthMargin) {
  auto scene = parseScene(kCullScene, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cull.json");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.gpuCullingOverride = culling;
  options.gpuCullingDepthMargin = depthMargin;
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  EXPECT_TRUE((*renderer)->update(0.0).ok());
  auto target = RenderTarget::create(320, 180, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  EXPECT_TRUE((*renderer)->render((*renderer)->initialCamera(), 320, 180).ok());
  return {target->readPixels(), (*renderer)->cullStats()};
}

TEST_P(GpuCull, CulledSceneIsTheUnculledOneBitForBit) {
  const CulledFrame off = renderCullScene(false);
  const CulledFrame on = renderCullScene(true);
  EXPECT_FALSE(off.stats.enabled);
  ASSERT_TRUE(on.stats.enabled);
  EXPECT_TRUE(on.image.pixels == off.image.pixels) << "culling changed the image";
  // Both hidden balls and the robot's hidden clusters; the ball in front is drawn.
  EXPECT_GE(on.stats.instancesOccluded, 1);
  EXPECT_GT(on.stats.clustersOccluded, 0);
  EXPECT_LT(on.stats.clustersOccluded, on.stats.clustersTested) << "the robot's head shows";
}

TEST_P(GpuCull, ANonConservativeDepthTestChangesTheImage) {
  const CulledFrame off = renderCullScene(false);
  const CulledFrame wrong = renderCullScene(true, -0.5f);
  EXPECT_FALSE(wrong.image.pixels == off.image.pixels)
      << "culling what lies in front of the wall should have removed the front ball";
}

ENGINE_INSTANTIATE_OFFSCREEN(GpuCull);

}  // namespace
