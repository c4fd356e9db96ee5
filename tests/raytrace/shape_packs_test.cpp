// RtScene's float rays test spheres and planes four at a time (shape_packs.h). Every
// answer must be the scalar loop's bit for bit: which shape, and its distance. Swept
// over random scenes at scales from 1e-3 to 1e5, with the rays where the two could
// part: grazing a sphere within a few ulps, starting on a surface, parallel to a
// plane, ending exactly at a hit, shapes repeated (ties), planes bounded to squares.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "raytrace/rt_scene.h"

namespace rt = engine::rt;

namespace {

struct ScalarAnswer {
  int material = -1;  // -1: no hit
  float t = 0.0f;
};

// The loop RtScene ran before the packs: one shape at a time, tMax shortened as it goes.
ScalarAnswer scalarNearest(const rt::RtScene& scene, rt::Ray<float> ray) {
  ScalarAnswer answer;
  for (const auto& sphere : scene.floatSpheres()) {
    if (auto t = sphere.intersect(ray)) {
      ray.tMax = *t;
      answer = {sphere.material, *t};
    }
  }
  for (std::size_t i = 0; i < scene.planeCount(); ++i) {
    const auto& plane = scene.floatPlanes()[i];
    const auto& square = scene.planeSquare(i);
    auto t = plane.intersect(ray);
    if (!t) continue;
    const glm::dvec3 local = glm::dvec3(ray(*t)) - square.point;
    if (square.extent > 0.0 && (std::abs(glm::dot(local, square.axisU)) > square.extent ||
                                std::abs(glm::dot(local, square.axisV)) > square.extent)) {
      continue;
    }
    ray.tMax = *t;
    answer = {plane.material, *t};
  }
  return answer;
}

class RandomShapes {
 public:
  explicit RandomShapes(std::uint32_t seed) : rng_(seed) {}

  rt::RtScene scene() {
    rt::RtScene scene;
    scale_ = std::pow(10.0, uniform(-3.0, 5.0));
    centre_ = randomUnit() * scale_ * uniform(0.0, 3.0);
    const int spheres = int(uniform(0.0, 11.99)), planes = int(uniform(0.0, 11.99));
    for (int i = 0; i < spheres; ++i) {
      // A repeat of the last sphere now and then: equal distances, the lower index wins.
      if (i > 0 && uniform(0.0, 1.0) < 0.15) {
        const auto& last = scene.floatSpheres().back();
        scene.addSphere(glm::dvec3(last.center), double(last.radius), scene.addMaterial({}));
        continue;
      }
      scene.addSphere(centre_ + randomUnit() * scale_ * uniform(0.0, 2.0), scale_ * uniform(0.01, 1.0),
                      scene.addMaterial({}));
    }
    for (int i = 0; i < planes; ++i) {
      const glm::dvec3 normal = uniform(0.0, 1.0) < 0.5 ? axis() : randomUnit();
      const double extent = uniform(0.0, 1.0) < 0.4 ? scale_ * uniform(0.1, 2.0) : 0.0;
      scene.addPlane(centre_ + randomUnit() * scale_ * uniform(0.0, 2.0), normal, scene.addMaterial({}), extent);
    }
    return scene;
  }

  // One of the kinds of ray that tell the two apart, if anything does.
  rt::Ray<float> ray(const rt::RtScene& scene) {
    rt::Ray<float> ray;
    ray.o = glm::vec3(centre_ + randomUnit() * scale_ * uniform(0.0, 4.0));
    ray.d = glm::vec3(randomUnit() * std::pow(10.0, uniform(-2.0, 2.0)));  // not unit
    const int kind = int(uniform(0.0, 5.99));
    if (kind == 1 && scene.sphereCount() > 0) graze(scene, ray);
    if (kind == 2 && scene.sphereCount() > 0) startOnSphere(scene, ray);
    if (kind == 3 && scene.planeCount() > 0) alongPlane(scene, ray);
    if (kind == 4) ray.d[int(uniform(0.0, 2.99))] = 0.0f;
    if (kind == 5) endAtAHit(scene, ray);
    return ray;
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  glm::dvec3 randomUnit() {
    std::normal_distribution<double> n;
    glm::dvec3 v;
    do {
      v = glm::dvec3(n(rng_), n(rng_), n(rng_));
    } while (glm::length(v) < 1e-6);
    return glm::normalize(v);
  }
  glm::dvec3 axis() {
    glm::dvec3 a(0.0);
    a[int(uniform(0.0, 2.99))] = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    return a;
  }
  const rt::Sphere<float>& anySphere(const rt::RtScene& scene) {
    return scene.floatSpheres()[std::size_t(uniform(0.0, double(scene.sphereCount()) - 1e-9))];
  }
  // Tangent to a sphere, its distance from the centre the radius give or take a few ulps;
  // a third of them at the sphere's extreme along an axis, in the face of its box.
  void graze(const rt::RtScene& scene, rt::Ray<float>& ray) {
    const auto& s = anySphere(scene);
    const glm::dvec3 n = uniform(0.0, 1.0) < 1.0 / 3.0 ? axis() : randomUnit();
    glm::dvec3 tangent = glm::cross(n, randomUnit());
    tangent = glm::normalize(tangent);
    const double ulps = std::round(uniform(-8.0, 8.0));
    const double r = double(s.radius) * (1.0 + ulps * 6e-8);
    const glm::dvec3 touch = glm::dvec3(s.center) + n * r;
    ray.o = glm::vec3(touch - tangent * double(s.radius) * uniform(0.5, 10.0));
    ray.d = glm::vec3(tangent);
  }
  void startOnSphere(const rt::RtScene& scene, rt::Ray<float>& ray) {
    const auto& s = anySphere(scene);
    ray.o = glm::vec3(glm::dvec3(s.center) + randomUnit() * double(s.radius));
  }
  // Parallel to a plane (a zero denominator for axis normals), in it or beside it.
  void alongPlane(const rt::RtScene& scene, rt::Ray<float>& ray) {
    const auto& p = scene.floatPlanes()[std::size_t(uniform(0.0, double(scene.planeCount()) - 1e-9))];
    const glm::vec3 d = ray.d - p.normal * glm::dot(ray.d, p.normal);
    if (glm::length(d) > 0.0f) ray.d = d;
    if (uniform(0.0, 1.0) < 0.5) ray.o = ray.o - p.normal * (glm::dot(ray.o, p.normal) - p.d);
  }
 public:
  // Toward a bounded plane's square at its edge, give or take a few ulps: where the
  // quick test of four rays at a time must leave the answer to the exact one.
  bool towardSquareEdge(const rt::RtScene& scene, rt::Ray<float>& ray) {
    std::vector<std::size_t> bounded;
    for (std::size_t i = 0; i < scene.planeCount(); ++i) {
      if (scene.planeSquare(i).extent > 0.0) bounded.push_back(i);
    }
    if (bounded.empty()) return false;
    const auto& q = scene.planeSquare(bounded[std::size_t(uniform(0.0, double(bounded.size()) - 1e-9))]);
    const double edge = q.extent * (1.0 + std::round(uniform(-8.0, 8.0)) * 6e-8);
    // Often on the axis itself, where the quick test's sum over the axes is tightest.
    const double across = uniform(0.0, 1.0) < 0.5 ? 0.0 : q.extent * uniform(-1.2, 1.2);
    const bool alongU = uniform(0.0, 1.0) < 0.5;
    const double sign = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    const glm::dvec3 target = q.point + (alongU ? q.axisU * edge * sign + q.axisV * across
                                                : q.axisV * edge * sign + q.axisU * across);
    ray.o = glm::vec3(target + randomUnit() * scale_ * uniform(0.1, 4.0));
    ray.d = glm::vec3(target - glm::dvec3(ray.o));
    ray.tMax = std::numeric_limits<float>::infinity();
    return true;
  }

  // The same line from up to a million times the scene's size away: where the root
  // boxes' margin around the spheres is thinnest against the rounding.
  void fromAfar(rt::Ray<float>& ray) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(ray.d));
    ray.o = glm::vec3(glm::dvec3(ray.o) - d * scale_ * std::pow(10.0, uniform(0.0, 6.0)));
    ray.tMax = std::numeric_limits<float>::infinity();
  }
  // scene() with `triangles` that are never hit (addUnhittableTriangle), built: its
  // float rays go through the root boxes.
  rt::RtScene sceneWithRootBoxes(int triangles) {
    rt::RtScene scene = this->scene();
    for (; triangles > 0; --triangles) addUnhittableTriangle(scene);
    scene.build();
    return scene;
  }
  // A triangle of zero area (never hit) in a group of its own or the static one, near
  // the shapes or far out: the scene then has a BVH, and float rays go through the
  // root boxes (RtAccel::RootHits), which also box the spheres.
  void addUnhittableTriangle(rt::RtScene& scene) {
    const double away = uniform(0.0, 1.0) < 0.5 ? 0.0 : scale_ * std::pow(10.0, uniform(0.0, 4.0));
    const glm::vec3 p(centre_ + randomUnit() * away);
    rt::RtMesh mesh;
    mesh.positions = {p, p, p};
    mesh.indices = {0, 1, 2};
    mesh.group = uniform(0.0, 1.0) < 0.5 ? 0 : scene.addGroup();
    ASSERT_TRUE(scene.addMesh(std::move(mesh)));
  }

 private:
  // tMax exactly at the scalar loop's hit, or one ulp either side of it.
  void endAtAHit(const rt::RtScene& scene, rt::Ray<float>& ray) {
    const ScalarAnswer hit = scalarNearest(scene, ray);
    if (hit.material < 0) return;
    const int step = int(uniform(0.0, 2.99)) - 1;
    ray.tMax = step == 0 ? hit.t : std::nextafter(hit.t, step > 0 ? INFINITY : 0.0f);
  }

  std::mt19937 rng_;
  double scale_ = 1.0;
  glm::dvec3 centre_{0.0};
};

// intersect() and intersectAny() of one ray against the scalar loop's answer, the
// distance bit for bit; counts the hits.
void expectTheScalarAnswer(const rt::RtScene& scene, const rt::Ray<float>& ray, std::uint32_t seed, int i,
                           std::uint64_t& hits) {
  const ScalarAnswer expected = scalarNearest(scene, ray);
  const auto hit = scene.intersect(ray);
  ASSERT_EQ(hit.has_value(), expected.material >= 0) << "seed " << seed << " ray " << i;
  ASSERT_EQ(scene.intersectAny(ray), expected.material >= 0) << "seed " << seed << " ray " << i;
  if (!hit) return;
  ++hits;
  ASSERT_EQ(hit->material, expected.material) << "seed " << seed << " ray " << i;
  ASSERT_EQ(std::bit_cast<std::uint32_t>(hit->t), std::bit_cast<std::uint32_t>(expected.t))
      << "seed " << seed << " ray " << i << ": " << hit->t << " against " << expected.t;
}

TEST(ShapePacks, FourAtATimeIsTheScalarLoopBitForBit) {
  std::uint64_t rays = 0, hits = 0, multiPackScenes = 0;
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    RandomShapes random(seed);
    const rt::RtScene scene = random.scene();
    for (int i = 0; i < 10000; ++i, ++rays) {
      rt::Ray<float> ray = random.ray(scene);
      if (i % 5 == 0) random.towardSquareEdge(scene, ray);  // where the square's quick test must defer
      expectTheScalarAnswer(scene, ray, seed, i, hits);
      if (HasFatalFailure()) return;
    }
    multiPackScenes += scene.sphereCount() + scene.planeCount() > 4 ? 1 : 0;
  }
  // The sweep must reach both answers and scenes of more than one pack.
  EXPECT_GT(hits, rays / 4);
  EXPECT_LT(hits, rays - rays / 8);
  EXPECT_GT(multiPackScenes, 100u);
}

// With triangles in the scene, float rays test the groups' root boxes and a box
// around all the spheres at once first (RtAccel::RootHits) and skip the spheres when
// that box is missed: the same answers as the scalar loop, bit for bit, grazing rays
// and rays from a million times the scene's size away included.
TEST(ShapePacks, PastTheRootBoxesTheScalarLoopBitForBit) {
  std::uint64_t rays = 0, hits = 0;
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    RandomShapes random(seed);
    const rt::RtScene scene = random.sceneWithRootBoxes(1 + int(seed % 3));
    for (int i = 0; i < 10000; ++i, ++rays) {
      rt::Ray<float> ray = random.ray(scene);
      if (i % 3 == 0) random.fromAfar(ray);
      expectTheScalarAnswer(scene, ray, seed, i, hits);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(hits, rays / 4);
  EXPECT_LT(hits, rays - rays / 8);
}

// RtScene::intersectCoherent (the Whitted tracer's camera rows, eight rays at a time)
// tests each lane's spheres and planes eight lanes at once (nearestShapesOfEight, every
// sphere whatever the root boxes say): each lane the scalar loop's answer, bit for
// bit, over the sweep above, grazing rays, rays from afar and rays at a square's edge
// side by side in one packet.
TEST(ShapePacks, EightRaysOfARowAreTheScalarLoopBitForBit) {
  constexpr int kLanes = rt::Bvh::kPacketSize;
  std::uint64_t rays = 0, hits = 0;
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    RandomShapes random(seed);
    const rt::RtScene scene = random.sceneWithRootBoxes(1 + int(seed % 3));
    for (int packet = 0; packet < 1250; ++packet) {
      rt::Ray<float> lanes[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        lanes[i] = random.ray(scene);
        if ((packet + i) % 3 == 0) random.fromAfar(lanes[i]);
        if ((packet + i) % 3 == 1) random.towardSquareEdge(scene, lanes[i]);
      }
      std::optional<rt::SurfaceInteraction<float>> together[kLanes];
      scene.intersectCoherent(lanes, together);
      for (int i = 0; i < kLanes; ++i, ++rays) {
        const ScalarAnswer expected = scalarNearest(scene, lanes[i]);
        ASSERT_EQ(together[i].has_value(), expected.material >= 0) << "seed " << seed << " packet " << packet << " lane " << i;
        if (!together[i]) continue;
        ++hits;
        ASSERT_EQ(together[i]->material, expected.material) << "seed " << seed << " packet " << packet << " lane " << i;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(together[i]->t), std::bit_cast<std::uint32_t>(expected.t))
            << "seed " << seed << " packet " << packet << " lane " << i << ": " << together[i]->t << " against "
            << expected.t;
      }
    }
  }
  EXPECT_GT(hits, rays / 4);
  EXPECT_LT(hits, rays - rays / 8);
}

// RtScene::intersectMany (the path tracer's batches: four rays to a pass over the
// shapes, one to a lane, or eight with AVX2 where there are no triangles, as here)
// gives each ray intersect()'s own answer, record and all, bit for bit, in batches of
// every size; a fifth of the rays aim at the edge of a bounded plane's square, where
// its quick test must defer to the exact one.
TEST(ShapePacks, FourRaysAtATimeAreEachRaysOwnAnswerBitForBit) {
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  std::uint64_t rays = 0, hits = 0, edgeRays = 0;
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    RandomShapes random(seed);
    const rt::RtScene scene = random.scene();
    std::mt19937 sizes(seed);
    for (int batch = 0; batch < 1000; ++batch) {
      const std::size_t count = 1 + sizes() % 17;
      std::vector<rt::Ray<float>> batchRays(count);
      for (rt::Ray<float>& ray : batchRays) {
        ray = random.ray(scene);
        if (sizes() % 5 == 0 && random.towardSquareEdge(scene, ray)) ++edgeRays;
      }
      std::vector<const rt::Ray<float>*> pointers;
      for (const rt::Ray<float>& ray : batchRays) pointers.push_back(&ray);
      std::vector<std::optional<rt::SurfaceInteraction<float>>> many(count);
      scene.intersectMany(pointers.data(), count, many.data());
      for (std::size_t i = 0; i < count; ++i, ++rays) {
        const auto one = scene.intersect(batchRays[i]);
        ASSERT_EQ(many[i].has_value(), one.has_value()) << "seed " << seed << " batch " << batch << " ray " << i;
        if (!one) continue;
        ++hits;
        ASSERT_EQ(many[i]->material, one->material) << "seed " << seed << " batch " << batch << " ray " << i;
        ASSERT_EQ(bits(many[i]->t), bits(one->t)) << "seed " << seed << " batch " << batch << " ray " << i;
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(bits(many[i]->p[c]), bits(one->p[c])) << "seed " << seed << " batch " << batch << " ray " << i;
          ASSERT_EQ(bits(many[i]->n[c]), bits(one->n[c])) << "seed " << seed << " batch " << batch << " ray " << i;
          ASSERT_EQ(bits(many[i]->ns[c]), bits(one->ns[c])) << "seed " << seed << " batch " << batch << " ray " << i;
          ASSERT_EQ(bits(many[i]->pError[c]), bits(one->pError[c])) << "seed " << seed << " batch " << batch;
        }
        ASSERT_EQ(bits(many[i]->uvPerMetre), bits(one->uvPerMetre)) << "seed " << seed << " batch " << batch;
        ASSERT_EQ(many[i]->uv, one->uv) << "seed " << seed << " batch " << batch << " ray " << i;
      }
    }
  }
  EXPECT_GT(hits, rays / 4);
  EXPECT_LT(hits, rays - rays / 8);
  EXPECT_GT(edgeRays, rays / 10);
}

}  // namespace
