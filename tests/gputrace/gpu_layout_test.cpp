// gputrace/gpu_layout.h: the flattened BVH8 is the CPU's tree. A small traversal of
// the flat arrays (what shaders/rt/trace.glsl does, in C++ with the CPU's own box
// and triangle tests) finds the CPU's closest hits, distance for distance, over
// random rays and rays aimed exactly at shared vertices and edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>

#include "../support/rt_queries.h"
#include "gputrace/gpu_layout.h"

namespace rt = engine::rt;
using engine::test::hitsAt;
using engine::test::leafVertex;
using engine::test::nearlyEqual;
using engine::test::ReferenceHit;

namespace {

rt::Bounds3f childBox(const rt::GpuNode& node, int k) {
  rt::Bounds3f b;
  for (int axis = 0; axis < 3; ++axis) {
    b.min[axis] = node.box[2 * axis + k / 4][k % 4];
    b.max[axis] = node.box[2 * (3 + axis) + k / 4][k % 4];
  }
  return b;
}

rt::Bounds3f childBox(const rt::GpuNode4& node, int k) {
  rt::Bounds3f b;
  for (int axis = 0; axis < 3; ++axis) {
    b.min[axis] = node.box[axis][k];
    b.max[axis] = node.box[3 + axis][k];
  }
  return b;
}

// A node's children of either width: (reference, box) for slot k.
std::uint32_t childRef(const rt::GpuSceneLayout& layout, std::uint32_t node, int k, rt::Bounds3f& box) {
  if (layout.width == 4) {
    box = childBox(layout.nodes4[node], k);
    return layout.nodes4[node].child[k];
  }
  box = childBox(layout.nodes[node], k);
  return layout.nodes[node].child[k / 4][k % 4];
}

// Depth first over the flat arrays from `root`, every child whose box the ray enters
// before the nearest hit; the nearest triangle hit shortens ray.tMax. Returns the
// deepest the stack got.
int traverseFlat(const rt::GpuSceneLayout& layout, std::uint32_t root, rt::Ray<float>& ray, ReferenceHit& best) {
  const rt::BoundsRay<float> boxes(ray);
  std::vector<std::uint32_t> stack{root};
  int deepest = 1;
  while (!stack.empty()) {
    const std::uint32_t ref = stack.back();
    stack.pop_back();
    if (!rt::Bvh::isLeaf(ref)) {
      for (int k = 0; k < layout.width; ++k) {
        rt::Bounds3f box;
        const std::uint32_t child = childRef(layout, ref, k, box);
        if (child != rt::Bvh::kNoChild && boxes.hits(box, ray)) stack.push_back(child);
      }
      deepest = std::max(deepest, int(stack.size()));
      continue;
    }
    const std::uint32_t leaf = rt::Bvh::leafIndex(ref);
    for (std::uint32_t lane = 0; lane < rt::Bvh::leafCount(ref); ++lane) {
      const rt::GpuLeaf& l = layout.leaves[leaf];
      if (auto hit = rt::intersectTriangle(ray, leafVertex(l, 0, int(lane)), leafVertex(l, 1, int(lane)), leafVertex(l, 2, int(lane)))) {
        ray.tMax = hit->t;
        best = {3, layout.order[4 * leaf + lane], hit->t};
      }
    }
  }
  return deepest;
}

class GpuLayout : public ::testing::TestWithParam<int> {};
INSTANTIATE_TEST_SUITE_P(Width, GpuLayout, ::testing::Values(8, 4));

TEST_P(GpuLayout, FlatTraversalFindsTheCpuBvhsClosestHits) {
  const rt::RtScene scene = engine::test::meshScene();
  const rt::GpuSceneLayout layout = rt::flattenScene(scene, GetParam());
  ASSERT_EQ(layout.width == 4 ? layout.nodes4.empty() : layout.nodes.empty(), false);
  ASSERT_EQ(layout.instances.size(), 2u) << "the empty group is left out";
  ASSERT_EQ(layout.triangles.size(), scene.triangleCount());
  ASSERT_EQ(layout.order.size(), 4 * layout.leaves.size());
  const std::vector<rt::Ray<float>> rays = engine::test::queryRays(4000, 7.0f, 5);
  int triangleHits = 0, mismatches = 0, ties = 0, deepest = 0;
  for (const rt::Ray<float>& ray : rays) {
    const ReferenceHit expected = engine::test::cpuClosestHit(scene, layout, ray);
    // The shapes' part is the CPU's own code; the triangles come from the flat arrays.
    rt::Ray<float> shortened = ray;
    ReferenceHit actual;
    for (std::size_t i = 0; i < scene.floatSpheres().size(); ++i) {
      if (auto t = scene.floatSpheres()[i].intersect(shortened)) actual = {1, std::uint32_t(i), shortened.tMax = *t};
    }
    if (auto t = scene.floatPlanes()[0].intersect(shortened)) actual = {2, 0, shortened.tMax = *t};
    for (const rt::GpuInstance& instance : layout.instances) {
      rt::Bounds3f bounds{glm::vec3(instance.boundsMin), glm::vec3(instance.boundsMax)};
      if (rt::BoundsRay<float>(shortened).hits(bounds, shortened)) {
        deepest = std::max(deepest, traverseFlat(layout, instance.root.x, shortened, actual));
      }
    }
    triangleHits += expected.kind == 3 ? 1 : 0;
    // Exactly the CPU's hit, or (a tie) another triangle at the same point.
    const bool exact = actual.kind == expected.kind && actual.index == expected.index && actual.t == expected.t;
    const bool tie = !exact && actual.kind == 3 && expected.kind == 3 && nearlyEqual(actual.t, expected.t) &&
                     hitsAt(layout, actual.index, ray, actual.t);
    ties += tie ? 1 : 0;
    mismatches += exact || tie ? 0 : 1;
    // And RtScene::intersect itself agrees with the reference it is compared with.
    const auto si = scene.intersect(ray);
    ASSERT_EQ(bool(si), expected.kind != 0);
    if (si) {
      ASSERT_EQ(si->t, expected.t);
    }
  }
  EXPECT_EQ(mismatches, 0) << "of " << rays.size() << " rays";
  EXPECT_GT(triangleHits, int(rays.size()) / 3);
  // The depth-first reference pushes all eight children at once; the GPU's stack,
  // sorted and popped per child, holds at most seven per level plus one.
  EXPECT_LE(deepest, layout.stackSize());
  std::printf("gpu layout %d wide: %zu rays, %d triangle hits, %d ties at shared edges, %zu nodes, %zu leaves, depth %d\n",
              layout.width, rays.size(), triangleHits, ties, layout.width == 4 ? layout.nodes4.size() : layout.nodes.size(),
              layout.leaves.size(), layout.depth);
}

// The rebased references point into the shared arrays: every interior child is a
// node after its parent's group start, every leaf block exists, and each triangle
// has exactly one slot.
TEST_P(GpuLayout, ReferencesStayInsideTheSharedArrays) {
  const rt::RtScene scene = engine::test::meshScene();
  const rt::GpuSceneLayout layout = rt::flattenScene(scene, GetParam());
  std::vector<int> slots(layout.triangles.size(), 0);
  for (std::uint32_t id : layout.order) {
    if (id == rt::Bvh::kNoChild) continue;
    ASSERT_LT(id, slots.size());
    ++slots[id];
  }
  EXPECT_EQ(std::count(slots.begin(), slots.end(), 1), std::ptrdiff_t(slots.size()));
  const std::size_t nodes = layout.width == 4 ? layout.nodes4.size() : layout.nodes.size();
  for (std::uint32_t n = 0; n < nodes; ++n) {
    for (int k = 0; k < layout.width; ++k) {
      rt::Bounds3f box;
      const std::uint32_t ref = childRef(layout, n, k, box);
      if (ref == rt::Bvh::kNoChild) continue;
      if (rt::Bvh::isLeaf(ref)) {
        EXPECT_LT(rt::Bvh::leafIndex(ref), layout.leaves.size());
      } else {
        EXPECT_GT(ref, n) << "children follow their parent";
        EXPECT_LT(ref, nodes);
      }
    }
  }
  EXPECT_EQ(layout.firstTriangle.size(), 3u);
  EXPECT_EQ(layout.firstTriangle[1], scene.bvh(0).triangleCount());
}

}  // namespace
