// The BVH against brute force on random rays (nearest hit and any hit), after a
// build, a refit to moved vertices and a rebuild; build and refit times of a
// 10k-triangle mesh are printed for the record.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include <tbb/task_arena.h>

#include "raytrace/bvh.h"
#include "raytrace/rt_scene.h"
#include "isa_sweep.h"

namespace rt = engine::rt;

namespace {

// Small random triangles in a box, plus a few long thin ones that cross it (they
// stress the SAH's bins and the refit's bounds).
std::vector<rt::TriangleVerts> randomSoup(int count, std::mt19937& rng) {
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-0.8f, 0.8f);
  std::vector<rt::TriangleVerts> tris;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    const float stretch = i % 50 == 0 ? 10.0f : 1.0f;
    tris.push_back({c + glm::vec3(off(rng), off(rng), off(rng)) * stretch, c + glm::vec3(off(rng), off(rng), off(rng)),
                    c + glm::vec3(off(rng), off(rng), off(rng))});
  }
  return tris;
}

template <typename T>
std::optional<rt::BvhHit<T>> bruteForce(const std::vector<rt::TriangleVerts>& tris, rt::Ray<T> ray) {
  std::optional<rt::BvhHit<T>> best;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    if (auto h = rt::intersectTriangle(ray, rt::Vec3<T>(tris[i].p0), rt::Vec3<T>(tris[i].p1), rt::Vec3<T>(tris[i].p2))) {
      ray.tMax = h->t;
      best = rt::BvhHit<T>{*h, std::uint32_t(i)};
    }
  }
  return best;
}

template <typename T>
void expectMatchesBruteForceOnce(const rt::Bvh& bvh, const std::vector<rt::TriangleVerts>& tris, std::mt19937& rng,
                                 int rayCount) {
  std::uniform_real_distribution<double> pos(-14.0, 14.0), dir(-1.0, 1.0), len(1.0, 30.0);
  int hits = 0, mismatches = 0, anyMismatches = 0;
  for (int i = 0; i < rayCount; ++i) {
    rt::Ray<T> ray{rt::Vec3<T>(T(pos(rng)), T(pos(rng)), T(pos(rng))), rt::Vec3<T>(T(dir(rng)), T(dir(rng)), T(dir(rng)))};
    if (i % 3 == 0) ray.tMax = T(len(rng) / glm::length(glm::dvec3(ray.d)));
    const auto expected = bruteForce(tris, ray);
    const auto actual = bvh.intersect(ray);
    hits += expected ? 1 : 0;
    if (bool(expected) != bool(actual) || (expected && expected->hit.t != actual->hit.t)) ++mismatches;
    if (bvh.intersectAny(ray) != bool(expected)) ++anyMismatches;
  }
  EXPECT_EQ(mismatches, 0) << "of " << rayCount << " rays, " << hits << " hits";
  EXPECT_EQ(anyMismatches, 0);
  EXPECT_GT(hits, rayCount / 10) << "the rays should mostly hit something";
}

// Every traversal this CPU can run: SSE always, AVX2 and its AVX-512VL compile where
// it has them (float only).
constexpr std::initializer_list<rt::Bvh::Isa> kIsas = {rt::Bvh::Isa::kSse2, rt::Bvh::Isa::kAvx2,
                                                       rt::Bvh::Isa::kAvx512};

template <typename T>
void expectMatchesBruteForce(const rt::Bvh& bvh, const std::vector<rt::TriangleVerts>& tris, std::mt19937& rng,
                             int rayCount) {
  forEachIsa(kIsas, [&] { expectMatchesBruteForceOnce<T>(bvh, tris, rng, rayCount); });
}

template <typename T>
class BvhTest : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(BvhTest, Precisions);

TYPED_TEST(BvhTest, MatchesBruteForceAfterBuildRefitAndRebuild) {
  using T = TypeParam;
  std::mt19937 rng(42);
  std::vector<rt::TriangleVerts> tris = randomSoup(3000, rng);
  rt::Bvh bvh;
  bvh.build(tris);
  EXPECT_EQ(bvh.triangleCount(), tris.size());
  EXPECT_LE(bvh.depth(), 64);
  expectMatchesBruteForce<T>(bvh, tris, rng, 4000);

  // Move every vertex (as skinning would), refit, test; then rebuild and test again.
  std::normal_distribution<float> jitter(0.0f, 0.5f);
  for (auto& t : tris) {
    const glm::vec3 shift(jitter(rng), jitter(rng), jitter(rng));
    t.p0 += shift;
    t.p1 += shift + glm::vec3(jitter(rng)) * 0.2f;
    t.p2 += shift;
  }
  bvh.refit(tris);
  expectMatchesBruteForce<T>(bvh, tris, rng, 4000);
  bvh.build(tris);
  expectMatchesBruteForce<T>(bvh, tris, rng, 2000);
}

// A refit to the positions the tree was built from gives the build's boxes bit for
// bit: each is the exact bounds of the triangles below it, empty slots left empty.
// (A refit once took an empty slot's inverted box as two points, and every node above
// a partly filled one grew to the whole of space: still correct, never culled.)
TEST(Bvh, RefitToTheSamePositionsKeepsEveryBox) {
  std::mt19937 rng(5);
  for (const int count : {1, 3, 5, 37, 300, 5000}) {
    const std::vector<rt::TriangleVerts> tris = randomSoup(count, rng);
    rt::Bvh bvh;
    bvh.build(tris);
    const std::vector<rt::Bvh::Node> built(bvh.view().nodes, bvh.view().nodes + bvh.nodeCount());
    const rt::Bounds3f root = bvh.bounds();
    bvh.refit(tris);
    ASSERT_EQ(bvh.nodeCount(), built.size()) << count << " triangles";
    // A tree of one leaf has no nodes, and memcmp must not see its null pointers.
    if (!built.empty()) {
      ASSERT_EQ(std::memcmp(built.data(), bvh.view().nodes, built.size() * sizeof(rt::Bvh::Node)), 0) << count << " triangles";
    }
    EXPECT_EQ(bvh.bounds().min, root.min);
    EXPECT_EQ(bvh.bounds().max, root.max);
  }
}

// A floor of two large triangles with boxes standing on it: each floor triangle's leaf
// has a flat box (no height), so that rays leaving the floor (shadow rays, bounces)
// start outside it and enter it only if they go down. The SAH alone put the floor
// into a leaf with triangles of the boxes, whose box then had height and held every
// such ray's origin; without bvh.cpp's flatGroupFirst this test fails on 14 of its 40
// seeds.
TEST(Bvh, AFloorsTrianglesGetFlatLeavesOfTheirOwn) {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> at(-45.0f, 45.0f), size(0.3f, 2.0f);
    const float e = 50.0f;
    std::vector<rt::TriangleVerts> tris = {{{-e, 0, -e}, {e, 0, -e}, {e, 0, e}}, {{-e, 0, -e}, {e, 0, e}, {-e, 0, e}}};
    for (int box = 0; box < 40; ++box) {
      const glm::vec3 lo(at(rng), 0.0f, at(rng)), hi = lo + glm::vec3(size(rng), size(rng), size(rng));
      const auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
      for (const auto& q : {std::array{0, 1, 3, 2}, std::array{4, 6, 7, 5}, std::array{0, 4, 5, 1},
                            std::array{2, 3, 7, 6}, std::array{0, 2, 6, 4}, std::array{1, 5, 7, 3}}) {
        tris.push_back({corner(q[0]), corner(q[1]), corner(q[2])});
        tris.push_back({corner(q[0]), corner(q[2]), corner(q[3])});
      }
    }
    rt::Bvh bvh;
    bvh.build(tris);
    const rt::Bvh::View view = bvh.view();
    int floorLeaves = 0;
    for (std::size_t n = 0; n < bvh.nodeCount(); ++n) {
      const rt::Bvh::Node& node = view.nodes[n];
      for (int k = 0; k < rt::Bvh::kWidth; ++k) {
        const std::uint32_t ref = node.child[k];
        if (ref == rt::Bvh::kNoChild || !rt::Bvh::isLeaf(ref)) continue;
        bool floor = false;
        for (std::uint32_t lane = 0; lane < rt::Bvh::leafCount(ref); ++lane) {
          floor = floor || view.order[4 * rt::Bvh::leafIndex(ref) + lane] < 2;
        }
        if (!floor) continue;
        ++floorLeaves;
        EXPECT_EQ(node.box[4][k], 0.0f) << "seed " << seed << ": a floor leaf's box reaches y = " << node.box[4][k];
      }
    }
    EXPECT_GE(floorLeaves, 1) << "seed " << seed;
  }
}

TEST(Bvh, EmptyAndDegenerateInputs) {
  rt::Bvh bvh;
  bvh.build({});
  EXPECT_TRUE(bvh.empty());
  EXPECT_FALSE(bvh.intersect(rt::Ray<float>{}));
  EXPECT_FALSE(bvh.intersectAny(rt::Ray<float>{}));
  // 100 copies of one triangle (coincident centroids) and a zero-area one.
  std::vector<rt::TriangleVerts> same(100, rt::TriangleVerts{{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}});
  same.push_back({{0, 0, 3}, {0, 0, 3}, {0, 0, 3}});
  bvh.build(same);
  const auto hit = bvh.intersect(rt::Ray<float>{glm::vec3(0), glm::vec3(0, 0, 1)});
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->hit.t, 5.0f);
}

// Watertightness through the whole BVH, whose leaves test four triangles at once in
// float with a scalar double fallback where an edge function is exactly zero: a
// 16 x 16 grid of quads at integer coordinates (two triangles each, so every interior
// edge and vertex is shared), rays from integer origins aimed exactly at every vertex
// and every edge midpoint, where the edge functions are exactly zero. None may slip
// through, and each must agree with brute force on the distance.
TEST(Bvh, RaysAtSharedEdgesAndVerticesNeverSlipThroughTheLeaves) {
  constexpr int kSide = 16;
  std::vector<rt::TriangleVerts> tris;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const glm::vec3 a(x, y, 7), b(x + 1, y, 7), c(x, y + 1, 7), d(x + 1, y + 1, 7);
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  }
  rt::Bvh bvh;
  bvh.build(tris);
  forEachIsa(kIsas, [&] {
    int rays = 0, misses = 0, disagreements = 0;
    for (const glm::vec3 origin : {glm::vec3(8, 8, 0), glm::vec3(-3, 2, -1), glm::vec3(20, -5, 2)}) {
      for (int y = 1; y < 2 * kSide; ++y) {
        for (int x = 1; x < 2 * kSide; ++x) {
          const glm::vec3 target(0.5f * float(x), 0.5f * float(y), 7.0f);  // vertices, edge midpoints, quad centres
          const rt::Ray<float> ray{origin, target - origin};
          const auto hit = bvh.intersect(ray);
          const auto expected = bruteForce(tris, ray);
          ++rays;
          misses += hit ? 0 : 1;
          disagreements += bool(hit) == bool(expected) && (!hit || hit->hit.t == expected->hit.t) ? 0 : 1;
          misses += bvh.intersectAny(ray) ? 0 : 1;
        }
      }
    }
    EXPECT_EQ(misses, 0) << "of " << rays << " rays";
    EXPECT_EQ(disagreements, 0);
  });
}

// Large meshes for the parallel build: a random soup, a terrain-like grid and a pile
// of triangles sharing one centroid (the object median's path).
std::vector<std::vector<rt::TriangleVerts>> largeMeshes(std::mt19937& rng) {
  std::vector<std::vector<rt::TriangleVerts>> meshes;
  meshes.push_back(randomSoup(150000, rng));
  std::vector<rt::TriangleVerts> grid;
  constexpr int kSide = 300;
  const auto at = [](int x, int z) {
    return glm::vec3(float(x), std::sin(0.1f * float(x)) * std::cos(0.07f * float(z)), float(z));
  };
  for (int z = 0; z < kSide; ++z) {
    for (int x = 0; x < kSide; ++x) {
      grid.push_back({at(x, z), at(x, z + 1), at(x + 1, z)});
      grid.push_back({at(x + 1, z), at(x, z + 1), at(x + 1, z + 1)});
    }
  }
  meshes.push_back(std::move(grid));
  std::vector<rt::TriangleVerts> pile;
  std::uniform_real_distribution<float> spread(0.01f, 1.0f);
  for (int i = 0; i < 40000; ++i) {
    const glm::vec3 d(spread(rng), spread(rng), spread(rng));
    pile.push_back({-d, d, glm::vec3(d.x, -d.y, d.z) * 0.5f});  // every box centred on the origin
  }
  meshes.push_back(std::move(pile));
  return meshes;
}

void expectSameTree(const rt::Bvh& a, const rt::Bvh& b, const std::string& what) {
  ASSERT_EQ(a.nodeCount(), b.nodeCount()) << what;
  ASSERT_EQ(a.leafCount(), b.leafCount()) << what;
  EXPECT_EQ(a.depth(), b.depth()) << what;
  const rt::Bvh::View va = a.view(), vb = b.view();
  EXPECT_EQ(va.root, vb.root) << what;
  EXPECT_EQ(std::memcmp(va.nodes, vb.nodes, a.nodeCount() * sizeof(rt::Bvh::Node)), 0) << what;
  EXPECT_EQ(std::memcmp(va.leaves, vb.leaves, a.leafCount() * sizeof(rt::Bvh::Triangle4)), 0) << what;
  EXPECT_EQ(std::memcmp(va.order, vb.order, a.leafCount() * 4 * sizeof(std::uint32_t)), 0) << what;
}

// The builder splits large nodes' two sides and its passes over their primitives
// across threads (bvh.cpp: buildTop, reduceOver, forParts). The tree must be the same
// bytes as the one built all on one thread, or images would depend on the core count:
// at the default grain and at a grain of 64 (thousands of parts and subtrees to
// stitch), on one thread and on four (more than the cores, so that they interleave).
// Then rays against brute force on the parallel build.
TEST(Bvh, BuildsTheSameTreeInParallelAsOnOneThread) {
  std::mt19937 rng(11);
  const auto meshes = largeMeshes(rng);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    rt::Bvh serial;
    serial.build(meshes[m], rt::Bvh::kSerial);
    for (const std::size_t grain : {rt::Bvh::kParallelGrain, std::size_t(64)}) {
      for (const int threads : {1, 4}) {
        rt::Bvh parallel;
        tbb::task_arena(threads).execute([&] { parallel.build(meshes[m], grain); });
        expectSameTree(serial, parallel, "mesh " + std::to_string(m) + ", grain " + std::to_string(grain) + ", " +
                                             std::to_string(threads) + " threads");
      }
    }
  }
  rt::Bvh soup;
  soup.build(meshes[0], 64);
  expectMatchesBruteForce<float>(soup, meshes[0], rng, 200);
}

// Meshes made from mt19937's integers alone (no distribution, no libm), so that every
// compiler and library makes the same floats: a soup on a coarse lattice, with many
// coordinates exactly 0 and -0 and many repeated; a grid of integer heights with flat
// stretches (the flat-leaf split); a floor of quads with boxes standing on it; and
// triangles that share one centroid (the object median).
std::vector<std::vector<rt::TriangleVerts>> latticeMeshes() {
  std::mt19937 rng(2026);
  const auto coordinate = [&] {
    const int v = int(rng() % 41) - 20;  // -20..20 tenths
    if (v == 0) return (rng() & 1) ? -0.0f : 0.0f;
    return float(v) * 0.1f;
  };
  // x, then y, then z: a function's arguments are evaluated in no fixed order (g++
  // and clang differ), the statements here in theirs.
  const auto draw = [](const auto& next) {
    const float x = next();
    const float y = next();
    return glm::vec3(x, y, next());
  };
  std::vector<std::vector<rt::TriangleVerts>> meshes(4);
  for (int i = 0; i < 30000; ++i) {
    const glm::vec3 c = draw(coordinate) * 5.0f;
    const glm::vec3 a = c + draw(coordinate);
    const glm::vec3 b = c + draw(coordinate);
    meshes[0].push_back({a, b, c + draw(coordinate)});
  }
  std::vector<int> height(101 * 101);
  for (int& h : height) h = int(rng() % 7) < 4 ? 0 : int(rng() % 5);
  const auto at = [&](int x, int z) { return glm::vec3(float(x), float(height[std::size_t(z * 101 + x)]), float(z)); };
  for (int z = 0; z < 100; ++z) {
    for (int x = 0; x < 100; ++x) {
      meshes[1].push_back({at(x, z), at(x, z + 1), at(x + 1, z)});
      meshes[1].push_back({at(x + 1, z), at(x, z + 1), at(x + 1, z + 1)});
    }
  }
  for (int z = -20; z < 20; ++z) {
    for (int x = -20; x < 20; ++x) {
      const glm::vec3 p(float(x), 0.0f, float(z));
      meshes[2].push_back({p, p + glm::vec3(0, 0, 1), p + glm::vec3(1, 0, 0)});
      meshes[2].push_back({p + glm::vec3(1, 0, 0), p + glm::vec3(0, 0, 1), p + glm::vec3(1, 0, 1)});
    }
  }
  for (int b = 0; b < 300; ++b) {
    const float x = float(int(rng() % 40) - 20);
    const glm::vec3 lo(x, 0.0f, float(int(rng() % 40) - 20));
    const glm::vec3 hi = lo + draw([&] { return float(1 + rng() % 3); });
    for (int axis = 0; axis < 3; ++axis) {  // two faces per axis, two triangles each
      for (const float side : {lo[axis], hi[axis]}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        glm::vec3 q[4];
        for (int k = 0; k < 4; ++k) {
          q[k][axis] = side;
          q[k][u] = (k & 1) ? hi[u] : lo[u];
          q[k][v] = (k & 2) ? hi[v] : lo[v];
        }
        meshes[2].push_back({q[0], q[1], q[2]});
        meshes[2].push_back({q[1], q[3], q[2]});
      }
    }
  }
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 d = draw([&] { return float(1 + rng() % 100) * 0.01f; });
    meshes[3].push_back({-d, d, glm::vec3(d.x, -d.y, d.z) * 0.5f});
  }
  return meshes;
}

// FNV-1a over a tree's every field: the nodes' boxes and children, the leaves, the
// slots, the root and the depth.
std::uint64_t treeHash(const rt::Bvh& bvh) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
      h ^= static_cast<const unsigned char*>(data)[i];
      h *= 1099511628211ull;
    }
  };
  const rt::Bvh::View v = bvh.view();
  for (std::size_t n = 0; n < bvh.nodeCount(); ++n) {
    mix(v.nodes[n].box, sizeof v.nodes[n].box);
    mix(v.nodes[n].child, sizeof v.nodes[n].child);
  }
  mix(v.leaves, bvh.leafCount() * sizeof(rt::Bvh::Triangle4));
  mix(v.order, bvh.leafCount() * 4 * sizeof(std::uint32_t));
  mix(&v.root, sizeof v.root);
  const int depth = bvh.depth();
  mix(&depth, sizeof depth);
  return h;
}

// The builder's output, pinned. A change meant to keep every tree (a faster binning, a
// parallel build) must leave these hashes as they are, which a test of the trees'
// answers alone would not show; a change meant to build other trees updates them and
// says why. These are the trees of the scalar builder of 77b5d2f, which the SSE
// binning (bvh.cpp: binPrims, SimdBox) keeps bit for bit.
TEST(Bvh, TreesArePinned) {
  const auto meshes = latticeMeshes();
  const std::uint64_t pinned[] = {0x9543c1d52e5bb1d6ull, 0x8b81f7c08c24250dull, 0x22a4490da87a0794ull, 0x71c94c2e3789b884ull};
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    rt::Bvh bvh;
    bvh.build(meshes[m]);
    EXPECT_EQ(treeHash(bvh), pinned[m]) << "mesh " << m << " (" << meshes[m].size() << " triangles): 0x" << std::hex
                                        << treeHash(bvh);
  }
}

// At a grain of 1 every node past four triangles is built and binned in parts, small
// nodes too, whose fewer bins are then summed with TBB's identity of all 32.
TEST(Bvh, BuildsTheSameTreeInPartsOfOne) {
  for (const auto& mesh : latticeMeshes()) {
    rt::Bvh serial, parts;
    serial.build(mesh, rt::Bvh::kSerial);
    tbb::task_arena(4).execute([&] { parts.build(mesh, 1); });
    expectSameTree(serial, parts, std::to_string(mesh.size()) + " triangles in parts of 1");
  }
}

// A 10k-triangle grid (a wavy terrain patch): build and refit times for the report.
TEST(Bvh, BuildAndRefitTimesOfA10kTriangleMesh) {
  constexpr int kSide = 71;  // 70 x 70 quads = 9800 triangles
  rt::RtMesh mesh;
  for (int z = 0; z < kSide; ++z) {
    for (int x = 0; x < kSide; ++x) mesh.positions.emplace_back(x * 0.1f, std::sin(x * 0.3f) * std::cos(z * 0.2f), z * 0.1f);
  }
  for (int z = 0; z + 1 < kSide; ++z) {
    for (int x = 0; x + 1 < kSide; ++x) {
      const std::uint32_t i = std::uint32_t(z * kSide + x);
      mesh.indices.insert(mesh.indices.end(), {i, i + kSide, i + 1, i + 1, i + kSide, i + kSide + 1});
    }
  }
  rt::RtScene scene;
  auto id = scene.addMesh(mesh);
  ASSERT_TRUE(id) << id.error().message;
  const double build = scene.build();
  for (auto& p : mesh.positions) p.y += 0.05f * std::sin(p.x + p.z);
  ASSERT_TRUE(scene.updateMesh(*id, mesh.positions).ok());
  const double refit = scene.refit();
  std::printf("[ bvh      ] %zu triangles, %zu nodes, depth %d: build %.2f ms, refit %.2f ms\n", scene.triangleCount(),
              scene.bvh().nodeCount(), scene.bvh().depth(), build * 1e3, refit * 1e3);
  EXPECT_EQ(scene.triangleCount(), 9800u);
  // Straight down onto a vertex: the ray lies in the planes of some boxes' faces.
  const auto hit = scene.intersect(rt::Ray<float>{mesh.positions[35 * kSide + 35] + glm::vec3(0, 5, 0), glm::vec3(0, -1, 0)});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->p.y, mesh.positions[35 * kSide + 35].y, 1e-5f);
}

// Two levels: a static mesh in group 0 and two "characters" in groups of their own.
// One character moves (updateMesh + refit, so only its group refits); the scene's
// nearest hit and any hit must then equal brute force over all current triangles.
TEST(RtScene, GroupRefitMatchesBruteForce) {
  std::mt19937 rng(7);
  rt::RtScene scene;
  const auto meshOf = [](const std::vector<rt::TriangleVerts>& tris, int group) {
    rt::RtMesh m;
    for (const auto& t : tris) {
      const auto i = std::uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), {t.p0, t.p1, t.p2});
      m.indices.insert(m.indices.end(), {i, i + 1, i + 2});
    }
    m.group = group;
    return m;
  };
  const std::vector<rt::TriangleVerts> world = randomSoup(2000, rng);
  std::vector<rt::TriangleVerts> a = randomSoup(500, rng), b = randomSoup(500, rng);
  ASSERT_TRUE(scene.addMesh(meshOf(world, 0)).ok());
  const int ga = scene.addGroup(), gb = scene.addGroup();
  auto ida = scene.addMesh(meshOf(a, ga));
  ASSERT_TRUE(ida.ok());
  ASSERT_TRUE(scene.addMesh(meshOf(b, gb)).ok());
  EXPECT_FALSE(scene.addMesh(meshOf(b, 3)).ok()) << "group 3 does not exist";
  scene.build();
  EXPECT_EQ(scene.groupCount(), 3);
  EXPECT_EQ(scene.triangleCount(), 3000u);
  const std::size_t worldNodes = scene.bvh(0).nodeCount();

  // Character a walks 3 units and bends: every vertex moves.
  std::normal_distribution<float> jitter(0.0f, 0.3f);
  for (auto& t : a) {
    const glm::vec3 shift = glm::vec3(3.0f, 0.0f, 0.0f) + glm::vec3(jitter(rng), jitter(rng), jitter(rng));
    t.p0 += shift;
    t.p1 += shift;
    t.p2 += shift + glm::vec3(jitter(rng));
  }
  const rt::RtMesh moved = meshOf(a, ga);
  ASSERT_TRUE(scene.updateMesh(*ida, moved.positions).ok());
  scene.refit();
  EXPECT_EQ(scene.bvh(0).nodeCount(), worldNodes);

  std::vector<rt::TriangleVerts> all = world;
  all.insert(all.end(), a.begin(), a.end());
  all.insert(all.end(), b.begin(), b.end());
  std::uniform_real_distribution<float> pos(-14.0f, 14.0f), dir(-1.0f, 1.0f);
  int hits = 0, mismatches = 0, anyMismatches = 0;
  for (int i = 0; i < 3000; ++i) {
    const rt::Ray<float> ray{glm::vec3(pos(rng), pos(rng), pos(rng)), glm::vec3(dir(rng), dir(rng), dir(rng))};
    const auto expected = bruteForce(all, ray);
    const auto actual = scene.intersect(ray);
    hits += expected ? 1 : 0;
    if (bool(expected) != bool(actual) || (expected && expected->hit.t != actual->t)) ++mismatches;
    if (scene.intersectAny(ray) != bool(expected)) ++anyMismatches;
  }
  EXPECT_EQ(mismatches, 0) << hits << " hits";
  EXPECT_EQ(anyMismatches, 0);
  EXPECT_GT(hits, 300);
}

TEST(RtScene, RejectsBadMeshes) {
  rt::RtScene scene;
  rt::RtMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 3};
  EXPECT_FALSE(scene.addMesh(mesh).ok());
  mesh.indices = {0, 1};
  EXPECT_FALSE(scene.addMesh(mesh).ok());
  mesh.indices = {0, 1, 2};
  mesh.normals = {{0, 0, 1}};
  EXPECT_FALSE(scene.addMesh(mesh).ok());
  mesh.normals.clear();
  mesh.material = 5;
  EXPECT_FALSE(scene.addMesh(mesh).ok());
  mesh.material = 0;
  auto id = scene.addMesh(mesh);
  ASSERT_TRUE(id.ok());
  const std::vector<glm::vec3> wrong(2);
  EXPECT_FALSE(scene.updateMesh(*id, wrong).ok());
  EXPECT_FALSE(scene.updateMesh(*id + 1, mesh.positions).ok());
}

}  // namespace
