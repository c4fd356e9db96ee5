// RtScene::intersectCoherent (eight rays, each group's BVH walked for them together)
// against RtScene::intersect, ray by ray: the same hit or miss, the same distance bit
// for bit, and the same record, except where two triangles lie at exactly that
// distance and the packet names the other, or finds one an ulp or two nearer that the
// ray alone culled with its box (both must stay rare; none on the camera's rows). On demo.json's
// camera rows (the terrain, the characters, the crates, spheres and the plaza) and on
// random packets about its camera: coherent ones that share a traversal, and ones
// that cannot (mixed direction signs), which go one ray at a time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "raytrace/camera.h"
#include "raytrace/rt_scene.h"
#include "test_scenes.h"

namespace {

constexpr int kLanes = rt::Bvh::kPacketSize;
using Hit = std::optional<rt::SurfaceInteraction<float>>;

template <typename V>
bool sameBits(const V& a, const V& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool sameRecord(const rt::SurfaceInteraction<float>& a, const rt::SurfaceInteraction<float>& b) {
  return sameBits(a.p, b.p) && sameBits(a.pError, b.pError) && sameBits(a.n, b.n) && sameBits(a.ns, b.ns) &&
         a.material == b.material && sameBits(a.uv, b.uv) && sameBits(a.uv1, b.uv1) && sameBits(a.color, b.color) &&
         sameBits(a.uvPerMetre, b.uvPerMetre) && sameBits(a.dpdu, b.dpdu) && sameBits(a.dpdv, b.dpdv);
}

struct Tally {
  int rays = 0, hits = 0, ties = 0, nearer = 0;
};

// Each lane of one packet against intersect(); counts hits and same-distance ties.
void expectPacketIsOneByOne(const rt::RtScene& scene, const rt::Ray<float> (&rays)[kLanes], Tally& tally,
                            const std::string& what) {
  Hit together[kLanes];
  scene.intersectCoherent(rays, together);
  for (int i = 0; i < kLanes; ++i) {
    const Hit alone = scene.intersect(rays[i]);
    ++tally.rays;
    ASSERT_EQ(together[i].has_value(), alone.has_value()) << what << " lane " << i;
    if (!alone) continue;
    ++tally.hits;
    if (!sameBits(together[i]->t, alone->t)) {
      // A hit within an ulp or two of the nearest so far, behind a box the packet's
      // interval test enters and the ray's own just misses (its entry rounded to tMax):
      // the packet may find it; never a farther one, never one further off.
      const float ulps = (alone->t - together[i]->t) / (std::nextafter(alone->t, 1e30f) - alone->t);
      ASSERT_TRUE(ulps > 0.0f && ulps <= 4.0f) << what << " lane " << i << ": t " << together[i]->t << ", alone "
                                               << alone->t;
      ++tally.nearer;
      continue;
    }
    if (!sameRecord(*together[i], *alone)) ++tally.ties;
  }
}

TEST(IntersectCoherent, CameraRowsAreOneRayAtATime) {
  const rt::RtScene scene = sceneFile("demo.json");
  const rt::PinholeCamera camera(scene.camera(), 320, 180);
  Tally tally;
  for (int y = 0; y < 180; ++y) {
    for (int x = 0; x < 320; x += kLanes) {
      rt::Ray<float> rays[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        rays[i] = camera.clippedToFarPlane(camera.generateRay<float>(x + i + 0.5, y + 0.5));
      }
      expectPacketIsOneByOne(scene, rays, tally, "row " + std::to_string(y) + " from " + std::to_string(x));
      if (HasFatalFailure()) return;
    }
  }
  // Most of the view is the plaza, the terrain and the figures; the sky is the rest.
  EXPECT_GT(tally.hits, tally.rays / 2);
  EXPECT_LE(tally.ties, tally.hits / 1000) << "named another triangle at the same distance too often";
  EXPECT_EQ(tally.nearer, 0);
}

// Packets from points about the eye: coherent (a narrow cone, one octant, as the
// packet traversal takes), wide (any direction: mixed signs, traced one at a time),
// and lanes that start elsewhere (a shadow ray's spread of origins along a row).
TEST(IntersectCoherent, RandomPacketsAreOneRayAtATime) {
  const rt::RtScene scene = sceneFile("demo.json");
  std::mt19937 rng(14);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 eye(scene.camera().position);
  Tally tally;
  for (int packet = 0; packet < 20000; ++packet) {
    const int kind = packet % 3;
    const glm::vec3 axis = glm::normalize(glm::vec3(normal(rng), normal(rng) - 0.5f, normal(rng)));
    const float spread = kind == 1 ? 10.0f : 0.05f;
    rt::Ray<float> rays[kLanes];
    for (int i = 0; i < kLanes; ++i) {
      const glm::vec3 o = kind == 2 ? glm::vec3(8.0f * u(rng), 0.01f + 3.0f * (u(rng) + 1.0f), 8.0f * u(rng)) : eye;
      const glm::vec3 d = glm::normalize(axis + spread * glm::vec3(normal(rng), normal(rng), normal(rng)));
      rays[i] = rt::Ray<float>{rt::Vec3<float>(o), rt::Vec3<float>(d), packet % 7 == 0 ? 5.0f : 1e30f};
    }
    expectPacketIsOneByOne(scene, rays, tally, "packet " + std::to_string(packet));
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(tally.hits, tally.rays / 4);
  EXPECT_LE(tally.ties, tally.hits / 1000) << "named another triangle at the same distance too often";
  EXPECT_LE(tally.nearer, tally.hits / 10000) << "found hits an ulp nearer too often";
}

}  // namespace
