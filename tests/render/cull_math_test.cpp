// GPU culling's CPU twin (render/cull_math.h): clusters, the Hi-Z pyramid and the
// box test, checked against brute force. tests/render/gpu_cull_test.cpp checks the
// compute shaders against this twin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "render/cull_math.h"
#include "render/terrain_cull.h"
#include "terrain/lod.h"

using namespace engine;
using namespace engine::cull;

namespace {

// The renderer's camera: reverse-Z, zero-to-one depth.
glm::mat4 cullTestViewProjection(float aspect) {
  const glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(50.0f), aspect, 100.0f, 0.1f);
  return projection * glm::lookAt(glm::vec3(0.0f), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
}

TEST(CullMath, ClustersAreConsecutiveRunsOfAtMost128TrianglesWithTheirBounds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::vector<glm::vec3> positions(300);
  for (auto& p : positions) p = {u(rng), u(rng), u(rng)};
  std::vector<std::uint32_t> indices(3 * 1000 + 3 * 77);
  for (auto& i : indices) i = std::uint32_t(rng() % positions.size());
  std::vector<Cluster> out(5);  // a table with something before
  const ClusterRange range = appendClusters(positions, indices, 3 * 77, 3 * 1000, out);
  EXPECT_EQ(range.first, 5u);
  EXPECT_EQ(range.count, 8u);  // ceil(1000 / 128)
  ASSERT_EQ(out.size(), 5u + 8u + 1u);
  std::uint32_t next = 3 * 77;
  for (std::uint32_t c = 0; c < range.count; ++c) {
    const Cluster& k = out[range.first + c];
    EXPECT_EQ(k.firstIndex, next);
    EXPECT_LE(k.indexCount, 3 * kClusterTriangles);
    next += k.indexCount;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (std::uint32_t i = k.firstIndex; i < k.firstIndex + k.indexCount; ++i) {
      lo = glm::min(lo, positions[indices[i]]);
      hi = glm::max(hi, positions[indices[i]]);
    }
    EXPECT_EQ(k.lo, lo);  // tight: exactly the referenced vertices' bounds
    EXPECT_EQ(k.hi, hi);
  }
  EXPECT_EQ(next, 3u * 77 + 3 * 1000);
  const Cluster& whole = out[range.first + range.count];
  EXPECT_EQ(whole.firstIndex, 3u * 77);
  EXPECT_EQ(whole.indexCount, 3u * 1000);
}

// Every texel of every level is at most the depth of every pixel it stands for
// (min(p >> k, size - 1)): the pyramid never claims a depth nearer than one below.
TEST(CullMath, EveryPyramidTexelIsAtMostEveryPixelItCovers) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (auto [w, h] : {std::pair{1, 1}, {2, 1}, {7, 5}, {33, 17}, {64, 64}, {101, 3}, {1280 / 8, 720 / 8}}) {
    std::vector<float> depth(size_t(w) * size_t(h));
    for (float& d : depth) d = u(rng);
    const HiZ hiz = HiZ::build(depth, w, h);
    ASSERT_EQ(int(hiz.levels.size()), hizLevelCount(w, h));
    EXPECT_EQ(hiz.levelWidth(int(hiz.levels.size())), 1);
    EXPECT_EQ(hiz.levelHeight(int(hiz.levels.size())), 1);
    for (int level = 1; level <= int(hiz.levels.size()); ++level)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const int tx = std::min(x >> level, hiz.levelWidth(level) - 1), ty = std::min(y >> level, hiz.levelHeight(level) - 1);
          ASSERT_LE(hiz.at(level, tx, ty), depth[size_t(y * w + x)]) << w << "x" << h << " level " << level;
        }
  }
}

TEST(CullMath, ABoxIsCulledByTheFrustumOnlyWhenWhollyOutside) {
  View view;
  view.viewProjection = cullTestViewProjection(16.0f / 9.0f);
  const glm::mat4 id(1.0f);
  EXPECT_EQ(testBox(view, id, {-1, -1, -6}, {1, 1, -4}), Verdict::Visible);
  EXPECT_EQ(testBox(view, id, {-1, -1, 4}, {1, 1, 6}), Verdict::Frustum);        // behind the camera
  EXPECT_EQ(testBox(view, id, {-40, -1, -6}, {-30, 1, -4}), Verdict::Frustum);   // far left
  EXPECT_EQ(testBox(view, id, {-1, -1, -300}, {1, 1, -200}), Verdict::Frustum);  // beyond the far plane
  EXPECT_EQ(testBox(view, id, {-40, -1, -6}, {0, 1, -4}), Verdict::Visible);     // straddles the left plane
  EXPECT_EQ(testBox(view, id, {-1, -1, -1}, {1, 1, 1}), Verdict::Visible);       // around the camera
}

// A wall of depth covering the view: a box behind it is hidden, one in front or
// straddling it is not, nor one that pokes out beside a smaller wall.
TEST(CullMath, ABoxIsOccludedOnlyWhenWhollyBehind) {
  const int w = 160, h = 90;
  View view;
  view.viewProjection = cullTestViewProjection(float(w) / float(h));
  auto depthAt = [&](float z) {  // reverse-Z depth of a point on the axis at -z
    const glm::vec4 c = view.viewProjection * glm::vec4(0, 0, -z, 1);
    return c.z / c.w;
  };
  std::vector<float> depth(size_t(w * h), depthAt(10.0f));
  const HiZ full = HiZ::build(depth, w, h);
  view.hiz = &full;
  const glm::mat4 id(1.0f);
  EXPECT_EQ(testBox(view, id, {-1, -1, -13}, {1, 1, -11}), Verdict::Occluded);
  EXPECT_EQ(testBox(view, id, {-1, -1, -13}, {1, 1, -9.9f}), Verdict::Visible);  // its front pokes through
  EXPECT_EQ(testBox(view, id, {-1, -1, -9}, {1, 1, -8}), Verdict::Visible);
  // The wall over the left half only: a box behind the right half shows.
  for (int y = 0; y < h; ++y)
    for (int x = w / 2; x < w; ++x) depth[size_t(y * w + x)] = 0.0f;
  const HiZ half = HiZ::build(depth, w, h);
  view.hiz = &half;
  EXPECT_EQ(testBox(view, id, {-4, -1, -13}, {-3, 1, -11}), Verdict::Occluded);
  EXPECT_EQ(testBox(view, id, {3, -1, -13}, {4, 1, -11}), Verdict::Visible);
  EXPECT_EQ(testBox(view, id, {-1, -1, -13}, {1, 1, -11}), Verdict::Visible);  // across the wall's edge
  // A non-conservative margin culls the box that pokes through: what the image
  // tests (tests/render/gpu_cull_test.cpp) must then catch.
  view.hiz = &full;
  view.depthMargin = -0.1f;
  EXPECT_EQ(testBox(view, id, {-1, -1, -13}, {1, 1, -9.9f}), Verdict::Occluded);
}

// Brute force: random boxes over random blocky depth; every box called occluded
// has, at every pixel centre inside its projected bounds, a nearest depth below
// the depth there (so no fragment of anything inside it could pass GL_GREATER).
TEST(CullMath, OccludedBoxesAreBehindEveryPixelTheyCover) {
  const int w = 96, h = 54;
  View view;
  view.viewProjection = cullTestViewProjection(float(w) / float(h));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int occluded = 0, tested = 0;
  for (int round = 0; round < 20; ++round) {
    std::vector<float> depth(size_t(w * h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) depth[size_t(y * w + x)] = 0.01f + 0.02f * float(((x / 12) * 7 + (y / 9) * 3 + round) % 5);
    const HiZ hiz = HiZ::build(depth, w, h);
    view.hiz = &hiz;
    for (int i = 0; i < 500; ++i) {
      const glm::vec3 c(20.0f * (u(rng) - 0.5f), 12.0f * (u(rng) - 0.5f), -5.0f - 40.0f * u(rng));
      const glm::vec3 r = glm::vec3(0.1f) + 2.0f * glm::vec3(u(rng), u(rng), u(rng));
      ++tested;
      if (testBox(view, glm::mat4(1.0f), c - r, c + r) != Verdict::Occluded) continue;
      ++occluded;
      double nearest = 0.0;
      glm::dvec2 lo(1e30), hi(-1e30);
      for (int k = 0; k < 8; ++k) {
        const glm::vec3 p(k & 1 ? c.x + r.x : c.x - r.x, k & 2 ? c.y + r.y : c.y - r.y, k & 4 ? c.z + r.z : c.z - r.z);
        const glm::dvec4 q = glm::dmat4(view.viewProjection) * glm::dvec4(glm::dvec3(p), 1.0);
        nearest = std::max(nearest, q.z / q.w);
        lo = glm::min(lo, glm::dvec2(q) / q.w);
        hi = glm::max(hi, glm::dvec2(q) / q.w);
      }
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double sx = (x + 0.5) / w * 2.0 - 1.0, sy = (y + 0.5) / h * 2.0 - 1.0;
          if (sx < lo.x || sx > hi.x || sy < lo.y || sy > hi.y) continue;
          ASSERT_LT(nearest, depth[size_t(y * w + x)]) << "box " << i << " at pixel " << x << "," << y;
        }
    }
  }
  EXPECT_GT(occluded, tested / 20) << "the scene should hide a good share of the boxes";
  EXPECT_LT(occluded, tested) << "and show some";
}

TEST(CullMath, CullJobsMergesVisibleRunsAndEmptiesCulledInstances) {
  View view;
  view.viewProjection = cullTestViewProjection(1.0f);
  // Four clusters along x at z = -5: the two left ones outside the view.
  std::vector<Cluster> clusters;
  for (int i = 0; i < 4; ++i) {
    const float x0 = i < 2 ? -60.0f + 10.0f * float(i) : -1.0f + float(i - 2);
    clusters.push_back({{x0, -0.5f, -5.5f}, std::uint32_t(i * 384), {x0 + 0.9f, 0.5f, -4.5f}, 384});
  }
  clusters.push_back({{-60, -0.5f, -5.5f}, 0, {1, 0.5f, -4.5f}, 4 * 384});  // whole
  std::vector<Job> jobs(3);
  jobs[0].sphere = {0, 0, 0, -1};
  jobs[0].clusterCount = 4;
  jobs[1] = jobs[0];
  jobs[1].firstCommand = 4;
  jobs[1].sphere = {0, 0, 50, 1};  // behind the camera: the instance is culled
  jobs[2] = jobs[0];
  jobs[2].firstCommand = 8;
  jobs[2].flags = kInstanceOnly;
  std::vector<Command> commands(9, Command{7, 7, 7, 7, 7});
  Counters counters;
  cullJobs(jobs, clusters, view, commands, counters);
  EXPECT_EQ(commands[0].instanceCount, 0u);
  EXPECT_EQ(commands[1].instanceCount, 0u);
  EXPECT_EQ(commands[2].count, 2u * 384);  // the two visible clusters, merged
  EXPECT_EQ(commands[2].firstIndex, 2u * 384);
  EXPECT_EQ(commands[2].instanceCount, 1u);
  EXPECT_EQ(commands[3].count, 0u);
  for (int i = 4; i < 8; ++i) EXPECT_EQ(commands[size_t(i)].instanceCount, 0u);
  EXPECT_EQ(commands[8].count, 4u * 384);  // instance only: the whole range
  EXPECT_EQ(counters.instancesTested, 3u);
  EXPECT_EQ(counters.instancesFrustum, 1u);
  EXPECT_EQ(counters.clustersTested, 4u);
  EXPECT_EQ(counters.clustersFrustum, 2u);
}

}  // namespace

namespace {

// Instanced jobs (the terrain's patches): a run of visible clusters is one
// command of as many instances, from the job's first instance plus its index.
TEST(CullMath, InstancedJobsDrawRunsOfInstances) {
  View view;
  view.viewProjection = cullTestViewProjection(1.0f);
  std::vector<Cluster> clusters;
  for (int i = 0; i < 5; ++i) {
    const float x0 = i == 2 ? -60.0f : -2.0f + float(i) * 0.8f;  // the middle one off to the left
    clusters.push_back({{x0, -0.5f, -5.5f}, 0, {x0 + 0.5f, 0.5f, -4.5f}, 6144});
  }
  clusters.push_back({{-60, -0.5f, -5.5f}, 0, {2, 0.5f, -4.5f}, 6144});
  Job job;
  job.sphere = {0, 0, 0, -1};
  job.clusterCount = 5;
  job.flags = kInstances;
  job.firstInstance = 10;
  std::vector<Command> commands(5);
  Counters counters;
  cullJobs(std::span<const Job>(&job, 1), clusters, view, commands, counters);
  EXPECT_EQ(commands[0].count, 6144u);
  EXPECT_EQ(commands[0].instanceCount, 2u);
  EXPECT_EQ(commands[0].baseInstance, 10u);
  EXPECT_EQ(commands[1].instanceCount, 0u);
  EXPECT_EQ(commands[2].instanceCount, 0u);
  EXPECT_EQ(commands[3].instanceCount, 2u);
  EXPECT_EQ(commands[3].baseInstance, 13u);
  EXPECT_EQ(commands[4].instanceCount, 0u);
  EXPECT_EQ(counters.clustersFrustum, 1u);
}

// Every vertex terrain.vert places (its CPU mirror, patchVertices) lies in its
// patch's box, for every patch of a few views of a rough field.
TEST(CullMath, TerrainPatchBoxesHoldEveryVertex) {
  terrain::TerrainSettings settings;
  settings.seed = 7;
  settings.size = 1024.0;
  settings.spacing = 1.0;
  settings.heightScale = 150.0;
  settings.origin = glm::dvec3(-300.0, -20.0, 100.0);
  auto field = terrain::Terrain::create(settings);
  ASSERT_TRUE(field.ok()) << field.error().message;
  int patches = 0;
  double worst = 0.0;
  for (const glm::dvec3 eye : {glm::dvec3(0.0, 120.0, 400.0), glm::dvec3(200.0, 40.0, 900.0), glm::dvec3(-250.0, 300.0, 150.0)}) {
    terrain::LodCamera camera;
    camera.position = eye;
    camera.viewProjection = glm::perspective(1.0f, 16.0f / 9.0f, 0.5f, 10000.0f) *
                            glm::lookAt(glm::vec3(0.0f), glm::vec3(0.3f, -0.4f, -1.0f), glm::vec3(0, 1, 0));
    const terrain::LodSelection selection = terrain::selectLod(*field, camera, 2.0);
    for (const terrain::LodPatch& patch : selection.patches) {
      const Cluster box = terrainPatchBox(*field, selection, patch, 6144);
      ++patches;
      for (const glm::vec3& v : terrain::patchVertices(*field, selection, patch)) {
        const glm::vec3 below = box.lo - v, above = v - box.hi;
        worst = std::max({worst, double(below.x), double(below.y), double(below.z), double(above.x), double(above.y),
                          double(above.z)});
      }
    }
  }
  EXPECT_GT(patches, 50);
  // Outside by float rounding at most: far below the cull's relative margin.
  EXPECT_LE(worst, 1e-3) << "a vertex lies " << worst << " m outside its patch's box";
}

}  // namespace
