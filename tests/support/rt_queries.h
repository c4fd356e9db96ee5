#pragma once
// What the GPU layout's tests share (tests/gputrace/gpu_layout_test.cpp, the CPU
// twin; tests/gputrace/gpu_trace_test.cpp, the GPU): a two-level mesh scene, rays that
// include ones aimed exactly at shared vertices and edges, and the CPU's closest hit
// with the id the GPU layout gives it (RtScene::intersect's order of shapes).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "gputrace/gpu_layout.h"
#include "raytrace/rt_scene.h"

namespace engine::test {

// Triangles as a mesh of the scene's group: a 16 x 16 grid of quads (shared edges
// and vertices) with normals, and a soup of small random triangles.
inline rt::RtMesh gridMesh(float z, int group) {
  constexpr int kSide = 16;
  rt::RtMesh mesh;
  for (int y = 0; y <= kSide; ++y) {
    for (int x = 0; x <= kSide; ++x) {
      mesh.positions.emplace_back(float(x) - 8.0f, float(y) - 8.0f, z);
      mesh.normals.emplace_back(0.0f, 0.0f, -1.0f);
    }
  }
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const auto a = std::uint32_t(y * (kSide + 1) + x), b = a + 1, c = a + kSide + 1, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  mesh.group = group;
  return mesh;
}

inline rt::RtMesh soupMesh(int count, std::mt19937& rng, int group) {
  std::uniform_real_distribution<float> pos(-8.0f, 8.0f), off(-0.7f, 0.7f);
  rt::RtMesh mesh;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng) * 0.5f);
    for (int v = 0; v < 3; ++v) {
      mesh.positions.push_back(c + glm::vec3(off(rng), off(rng), off(rng)));
      mesh.indices.push_back(std::uint32_t(mesh.indices.size()));
    }
  }
  mesh.group = group;
  return mesh;
}

// Group 0: the grid at z = 7 and 1500 triangles; group 1: 500 more; an empty group;
// a sphere and an unbounded plane behind everything.
inline rt::RtScene meshScene() {
  std::mt19937 rng(11);
  rt::RtScene scene;
  (void)scene.addMesh(gridMesh(7.0f, 0));
  (void)scene.addMesh(soupMesh(1500, rng, 0));
  const int characters = scene.addGroup();
  (void)scene.addMesh(soupMesh(500, rng, characters));
  scene.addGroup();
  scene.addSphere({2.0, -1.0, 3.0}, 1.5, 0);
  scene.addPlane({0.0, 0.0, 12.0}, {0.0, 0.0, -1.0}, 0);
  scene.build();
  return scene;
}

// Random rays from around the scene (a third with a finite tMax), and rays from three
// origins aimed at each vertex, edge midpoint and quad centre of the grid mesh at z.
inline std::vector<rt::Ray<float>> queryRays(int randomCount, float gridZ, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), dir(-1.0f, 1.0f), len(1.0f, 30.0f);
  std::vector<rt::Ray<float>> rays;
  for (int i = 0; i < randomCount; ++i) {
    rt::Ray<float> ray{glm::vec3(pos(rng), pos(rng), pos(rng) - 5.0f), glm::vec3(dir(rng), dir(rng), dir(rng))};
    if (i % 3 == 0) ray.tMax = len(rng) / glm::length(ray.d);
    rays.push_back(ray);
  }
  for (const glm::vec3 origin : {glm::vec3(0.0f, 0.0f, -6.0f), glm::vec3(-11.0f, 3.0f, -2.0f), glm::vec3(9.0f, -7.0f, 1.0f)}) {
    for (int y = 0; y <= 32; ++y) {
      for (int x = 0; x <= 32; ++x) {
        const glm::vec3 target(0.5f * float(x) - 8.0f, 0.5f * float(y) - 8.0f, gridZ);
        rays.push_back(rt::Ray<float>{origin, target - origin});
      }
    }
  }
  return rays;
}

struct ReferenceHit {
  int kind = 0;  // 0 none, 1 sphere, 2 plane, 3 triangle (gpurt::HitKind's values)
  std::uint32_t index = 0;
  float t = 0.0f;
};

// RtScene::intersect, step by step, keeping which shape won: spheres, planes (on
// their squares), then every group's BVH, each with tMax shortened by the last hit.
inline ReferenceHit cpuClosestHit(const rt::RtScene& scene, const rt::GpuSceneLayout& layout, rt::Ray<float> ray) {
  ReferenceHit best;
  for (std::size_t i = 0; i < scene.floatSpheres().size(); ++i) {
    if (auto t = scene.floatSpheres()[i].intersect(ray)) best = {1, std::uint32_t(i), ray.tMax = *t};
  }
  for (std::size_t i = 0; i < scene.floatPlanes().size(); ++i) {
    auto t = scene.floatPlanes()[i].intersect(ray);
    if (!t) continue;
    const rt::RtScene::PlaneSquare& q = scene.planeSquare(i);
    const glm::dvec3 local = glm::dvec3(ray(*t)) - q.point;
    if (q.extent > 0.0 && (std::abs(glm::dot(local, q.axisU)) > q.extent || std::abs(glm::dot(local, q.axisV)) > q.extent)) continue;
    best = {2, std::uint32_t(i), ray.tMax = *t};
  }
  for (int g = 0; g < scene.groupCount(); ++g) {
    if (scene.bvh(g).empty() || !rt::BoundsRay<float>(ray).hits(scene.bvh(g).bounds(), ray)) continue;
    if (auto hit = scene.bvh(g).intersect(ray)) best = {3, layout.firstTriangle[std::size_t(g)] + hit->triangle, ray.tMax = hit->hit.t};
  }
  return best;
}

inline glm::vec3 leafVertex(const rt::GpuLeaf& leaf, int v, int lane) {
  return {leaf.p[3 * v][lane], leaf.p[3 * v + 1][lane], leaf.p[3 * v + 2][lane]};
}

// Within two ulps. The triangle test compares t against the nearest hit so far as
// tScaled against tMax * det, which rounds: of two triangles meeting where the ray
// hits (a shared vertex or edge), whose t differ in the last bit, the one visited
// last may win. Which is visited last is the traversal's order, not the tree's.
inline bool nearlyEqual(float a, float b) {
  return std::abs(a - b) <= 2.0f * std::numeric_limits<float>::epsilon() * std::abs(b);
}

// Whether triangle `id` of the layout is hit at distance t (nearlyEqual): of two
// triangles that meet where the ray hits, either is the right answer.
inline bool hitsAt(const rt::GpuSceneLayout& layout, std::uint32_t id, const rt::Ray<float>& ray, float t) {
  const auto slot = std::size_t(std::find(layout.order.begin(), layout.order.end(), id) - layout.order.begin());
  if (slot >= layout.order.size()) return false;
  const rt::GpuLeaf& l = layout.leaves[slot / 4];
  const int lane = int(slot % 4);
  rt::Ray<float> longer = ray;
  longer.tMax = std::numeric_limits<float>::infinity();
  auto hit = rt::intersectTriangle(longer, leafVertex(l, 0, lane), leafVertex(l, 1, lane), leafVertex(l, 2, lane));
  return hit && nearlyEqual(hit->t, t);
}

}  // namespace engine::test
