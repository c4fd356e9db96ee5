// The terrain split at the scene's ground (raytrace/ground_split.h): the plane chosen,
// the triangles moved (each once, with its own corners and attributes, no vertex
// left unused), and a scene traced with the split meeting what the whole one meets,
// bit for bit, for rays from everywhere, grazing the ground, and far away.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "raytrace/ground_split.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {
namespace {

SceneDesc sceneWithPlanes(const glm::dvec3& eye) {
  SceneDesc scene;
  scene.camera.position = eye;
  scene.materials.resize(2);
  scene.materials[1].layers.transmission = 0.5f;
  return scene;
}

PrimitiveDesc plane(const glm::dvec3& point, const glm::dvec3& normal, double extent, int material) {
  PrimitiveDesc p;
  p.type = PrimitiveType::Plane;
  p.point = point;
  p.normal = normal;
  p.extent = extent;
  p.material = material;
  return p;
}

TEST(GroundSplit, TheGroundIsTheLargestOpaquePlaneFacingTheCamera) {
  SceneDesc scene = sceneWithPlanes({1.0, 5.0, 2.0});
  EXPECT_FALSE(groundPlane(scene).has_value()) << "no plane";
  scene.primitives.push_back(plane({0, 2, 0}, {0, 1, 0}, 10.0, 0));
  scene.primitives.push_back(plane({0, 0, 0}, {0, 0, 2}, 100.0, 1));  // larger, but lets light through
  scene.primitives.push_back(plane({0, -1, 0}, {0, -3, 0}, 20.0, 0));  // the largest opaque, facing down
  auto ground = groundPlane(scene);
  ASSERT_TRUE(ground.has_value());
  EXPECT_EQ(ground->normal, glm::dvec3(0, 1, 0)) << "turned to the camera's side";
  EXPECT_DOUBLE_EQ(ground->offset, 1.0);
  EXPECT_DOUBLE_EQ(ground->signedDistance(scene.camera.position), 6.0);
  scene.camera.position = {0.0, -4.0, 0.0};
  ground = groundPlane(scene);
  ASSERT_TRUE(ground.has_value());
  EXPECT_EQ(ground->normal, glm::dvec3(0, -1, 0));
  EXPECT_DOUBLE_EQ(ground->signedDistance(scene.camera.position), 3.0);
  scene.camera.position = {7.0, -1.0, 3.0};  // in the largest one's plane: the next one
  ground = groundPlane(scene);
  ASSERT_TRUE(ground.has_value());
  EXPECT_DOUBLE_EQ(ground->offset, 2.0) << "the 10 wide plane at y = 2, seen from below";
  scene.primitives[2].extent = 0.0;  // unbounded: it reaches the far distance
  scene.camera.position = {0.0, 9.0, 0.0};
  EXPECT_DOUBLE_EQ(groundPlane(scene)->offset, 1.0);
}

// A mesh of `triangles` random triangles near the plane y = 0, some corners exactly
// on it or an ulp off, with every attribute a mesh may have.
RtMesh randomMesh(std::mt19937& rng, int triangles, int vertices) {
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f);
  std::uniform_int_distribution<int> kind(0, 5);
  RtMesh mesh;
  mesh.material = 3;
  mesh.group = 0;
  for (int v = 0; v < vertices; ++v) {
    float y = coord(rng);
    if (const int k = kind(rng); k == 0) {
      y = 0.0f;
    } else if (k == 1) {
      y = std::nextafter(0.0f, y);
    }
    mesh.positions.push_back({coord(rng), y, coord(rng)});
    mesh.normals.push_back({coord(rng), coord(rng), coord(rng)});
    mesh.uvs.push_back({coord(rng), coord(rng)});
    mesh.uvs1.push_back({coord(rng), coord(rng)});
    mesh.colors.push_back({coord(rng), coord(rng), coord(rng), coord(rng)});
  }
  std::uniform_int_distribution<std::uint32_t> index(0, std::uint32_t(vertices - 1));
  for (int i = 0; i < 3 * triangles; ++i) mesh.indices.push_back(index(rng));
  return mesh;
}

// A corner as everything the mesh says about it, bit for bit.
std::vector<float> cornerBits(const RtMesh& mesh, std::uint32_t v) {
  std::vector<float> out;
  for (int i = 0; i < 3; ++i) out.push_back(mesh.positions[v][i]);
  for (int i = 0; i < 3; ++i) out.push_back(mesh.normals[v][i]);
  for (int i = 0; i < 2; ++i) out.push_back(mesh.uvs[v][i]);
  for (int i = 0; i < 2; ++i) out.push_back(mesh.uvs1[v][i]);
  for (int i = 0; i < 4; ++i) out.push_back(mesh.colors[v][i]);
  return out;
}

std::vector<std::vector<float>> triangleBits(const RtMesh& mesh, std::size_t t) {
  return {cornerBits(mesh, mesh.indices[3 * t]), cornerBits(mesh, mesh.indices[3 * t + 1]),
          cornerBits(mesh, mesh.indices[3 * t + 2])};
}

void expectEveryVertexUsed(const RtMesh& mesh) {
  std::vector<bool> used(mesh.positions.size(), false);
  for (const std::uint32_t i : mesh.indices) {
    ASSERT_LT(i, mesh.positions.size());
    used[i] = true;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
  EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
  EXPECT_EQ(mesh.uvs1.size(), mesh.positions.size());
  EXPECT_EQ(mesh.colors.size(), mesh.positions.size());
}

// 2,000 random meshes: each triangle lands in exactly one part, in its order, with
// its corners' every attribute; the behind part holds just the triangles whose
// corners are all strictly behind (a corner on the plane keeps a triangle in front).
TEST(GroundSplit, EachTriangleMovesOnceWithItsCorners) {
  std::mt19937 rng(20261205);
  const GroundPlane ground{{0.0, 1.0, 0.0}, 0.0};
  int moved = 0, kept = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const RtMesh before = randomMesh(rng, 1 + trial % 40, 3 + trial % 25);
    RtMesh front = before;
    const RtMesh behind = takeTrianglesBehind(front, ground);
    EXPECT_EQ(behind.material, before.material);
    std::size_t b = 0, f = 0;
    for (std::size_t t = 0; t < before.indices.size() / 3; ++t) {
      bool allBehind = true;
      for (int c = 0; c < 3; ++c) allBehind = allBehind && before.positions[before.indices[3 * t + c]].y < 0.0f;
      const RtMesh& part = allBehind ? behind : front;
      std::size_t& at = allBehind ? b : f;
      ASSERT_LT(at, part.indices.size() / 3) << "trial " << trial;
      EXPECT_EQ(triangleBits(part, at), triangleBits(before, t)) << "trial " << trial << " triangle " << t;
      ++at;
    }
    EXPECT_EQ(b, behind.indices.size() / 3) << "trial " << trial;
    EXPECT_EQ(f, front.indices.size() / 3) << "trial " << trial;
    if (!behind.indices.empty()) {
      expectEveryVertexUsed(behind);
      expectEveryVertexUsed(front);
    } else {
      EXPECT_EQ(front.positions.size(), before.positions.size()) << "nothing moved: the mesh is left as it was";
    }
    moved += int(b);
    kept += int(f);
  }
  EXPECT_GT(moved, 1000);
  EXPECT_GT(kept, 1000);
}

// A heightfield like the terrain's: a grid of 2 m cells whose heights cross y = 0,
// under a square opaque plane at y = 0, as demo.json's valley lies under its plaza.
RtMesh valley(int cells) {
  RtMesh mesh;
  const float size = 2.0f;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const float x = (float(i) - 0.5f * float(cells)) * size, z = (float(j) - 0.5f * float(cells)) * size;
      const float y = 0.02f * (x * x + z * z) - 6.0f + std::sin(0.7f * x) * std::cos(0.4f * z);
      mesh.positions.push_back({x, y, z});
      mesh.normals.push_back(glm::normalize(glm::vec3(-0.04f * x, 1.0f, -0.04f * z)));
      mesh.uvs.push_back({x * 0.1f, z * 0.1f});
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  return mesh;
}

RtScene valleyScene(bool split) {
  RtScene scene;
  MaterialDesc ground;
  scene.addMaterial(ground);
  scene.addPlane({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 0, 12.0);
  scene.addSphere({3.0, 0.5, -2.0}, 0.5, 0);
  RtMesh mesh = valley(40);
  if (split) {
    RtMesh behind = takeTrianglesBehind(mesh, GroundPlane{{0.0, 1.0, 0.0}, 0.0});
    EXPECT_GT(behind.indices.size() / 3, 300u) << "the valley floor lies under the plane";
    behind.group = scene.addGroup();
    EXPECT_TRUE(scene.addMesh(std::move(behind)).ok());
  }
  EXPECT_TRUE(scene.addMesh(std::move(mesh)).ok());
  scene.build();
  EXPECT_EQ(scene.groupCount(), split ? 2 : 1);
  return scene;
}

template <typename T>
Ray<T> randomRay(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  glm::dvec3 o(40.0 * unit(rng), 20.0 * unit(rng), 40.0 * unit(rng));
  glm::dvec3 d(unit(rng), unit(rng), unit(rng));
  if (kind == 1) d.y = 1e-6 * unit(rng);                 // grazing the ground
  if (kind == 2) o = glm::dvec3(o.x, 2.6, o.z), d.y = -std::abs(d.y);  // a camera above it, looking down
  if (kind == 3) o *= 1e4;                                // far away, toward the valley
  if (kind == 3) d = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 10.0 - o;
  return Ray<T>{Vec3<T>(o), Vec3<T>(d)};
}

// The split changes only the order in which triangles are met. A box's entry distance
// rounds by about an ulp of t, so of two triangles within that of each other along a
// ray the one met first wins: on rays from 10^4 times the scene's size away (kind 3)
// that spans centimetres, and there the two nearest distances agree to 4 ulps. Every
// other ray meets the same hit bit for bit; where two triangles meet at it (a shared
// edge) either may be reported, and then the point is compared.
template <typename T>
void expectSameHits(const RtScene& whole, const RtScene& split, int rays) {
  std::mt19937 rng(7);
  int hits = 0, behindHits = 0, farApart = 0;
  for (int i = 0; i < rays; ++i) {
    const int kind = i % 4;
    const Ray<T> ray = randomRay<T>(rng, kind);
    const auto a = whole.intersect(ray), b = split.intersect(ray);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    EXPECT_EQ(whole.intersectAny(ray), split.intersectAny(ray)) << "ray " << i;
    if (!a) continue;
    ++hits;
    behindHits += a->p.y < T(0) ? 1 : 0;
    if (kind == 3) {
      const T ulp = std::nextafter(a->t, T(2) * a->t) - a->t;
      EXPECT_LE(std::abs(a->t - b->t), T(4) * ulp) << "ray " << i;
      farApart += a->t != b->t ? 1 : 0;
      continue;
    }
    ASSERT_EQ(std::memcmp(&a->t, &b->t, sizeof(T)), 0) << "ray " << i;
    EXPECT_EQ(a->p, b->p) << "ray " << i;
    if (a->n != b->n) continue;
    EXPECT_EQ(a->ns, b->ns) << "ray " << i;
    EXPECT_EQ(a->uv, b->uv) << "ray " << i;
    EXPECT_EQ(a->material, b->material) << "ray " << i;
  }
  EXPECT_GT(hits, rays / 4);
  EXPECT_GT(behindHits, rays / 50) << "rays reach the valley floor past the plane's edge";
  EXPECT_LT(farApart, rays / 1000);
}

TEST(GroundSplit, TheSplitSceneMeetsWhatTheWholeOneMeets) {
  const RtScene whole = valleyScene(false), split = valleyScene(true);
  expectSameHits<float>(whole, split, 200000);
  expectSameHits<double>(whole, split, 50000);
}

}  // namespace
}  // namespace engine::rt
