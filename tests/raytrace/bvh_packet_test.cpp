// Bvh::intersect8 against Bvh::intersect, ray by ray: the same nearest distance bit
// for bit, the same triangle or one that the ray meets at that same distance (a tie
// at a shared edge). Packets of a camera's 4 x 2 pixels from many places over a
// random soup, a terrain-like grid and a flat grid aimed exactly at its shared
// vertices and edges; origins spread a little (the interval of origins), tMax per
// lane (some exactly at the hit, where strictness shows), and incoherent packets,
// which intersect8 traces one ray at a time.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

#include "raytrace/bvh.h"
#include "isa_sweep.h"

namespace rt = engine::rt;

namespace {

std::vector<rt::TriangleVerts> soupOf(int count, std::mt19937& rng) {
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-0.8f, 0.8f);
  std::vector<rt::TriangleVerts> tris;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    tris.push_back({c + glm::vec3(off(rng), off(rng), off(rng)), c + glm::vec3(off(rng), off(rng), off(rng)),
                    c + glm::vec3(off(rng), off(rng), off(rng))});
  }
  return tris;
}

// A grid of quads at height(x, z), two triangles each, sharing every edge.
template <typename Height>
std::vector<rt::TriangleVerts> gridOf(int side, float cell, Height height) {
  std::vector<rt::TriangleVerts> tris;
  const auto at = [&](int x, int z) {
    const float px = (float(x) - 0.5f * float(side)) * cell, pz = (float(z) - 0.5f * float(side)) * cell;
    return glm::vec3(px, height(px, pz), pz);
  };
  for (int z = 0; z < side; ++z) {
    for (int x = 0; x < side; ++x) {
      tris.push_back({at(x, z), at(x + 1, z), at(x + 1, z + 1)});
      tris.push_back({at(x, z), at(x + 1, z + 1), at(x, z + 1)});
    }
  }
  return tris;
}

class PacketCheck {
 public:
  PacketCheck(const rt::Bvh& bvh, const std::vector<rt::TriangleVerts>& tris) : bvh_(bvh), tris_(tris) {}

  // Every lane of intersect8 against intersect; whether the packet path took them.
  void check(const std::array<rt::Ray<float>, 8>& rays) {
    std::array<rt::BvhHit<float>, 8> hits{};
    std::uint32_t mask = 0;
    const bool together = bvh_.tracePacket8(rays.data(), hits.data(), mask);
    if (!together) mask = bvh_.intersect8(rays, hits);
    (together ? packets : oneByOne)++;
    for (int lane = 0; lane < 8; ++lane) {
      const rt::Ray<float>& ray = rays[std::size_t(lane)];
      ++rays_;
      if (!answersAsOneRay(ray, (mask >> lane) & 1u, hits[std::size_t(lane)])) ++mismatches;
    }
  }

  int packets = 0, oneByOne = 0, mismatches = 0, ties = 0, hitCount = 0, boundary = 0;
  int rays() const { return rays_; }

 private:
  // The same nearest distance as intersect(), bit for bit, on the same triangle; or, where
  // the two traversals met two triangles within 2 ulps of each other in another order
  // (the watertight test's comparison with the nearest so far rounds in its own
  // scale), the other one, which the ray must then meet at exactly the distance given.
  // Hits lie strictly within (0, tMax). intersect() itself may let a hit at exactly
  // tMax through (when the box test lets the leaf through); the packet path never does.
  bool answersAsOneRay(const rt::Ray<float>& ray, bool hit, const rt::BvhHit<float>& h) {
    const auto single = bvh_.intersect(ray);
    if (single && !(single->hit.t < ray.tMax)) {
      ++boundary;
      // The packet path stays within (0, tMax); one by one, intersect8 is intersect().
      return !hit || h.hit.t < ray.tMax || (h.triangle == single->triangle && h.hit.t == single->hit.t);
    }
    if (hit != single.has_value()) return false;
    if (!hit) return true;
    ++hitCount;
    if (!(h.hit.t < ray.tMax)) return false;
    if (h.triangle == single->triangle) {
      return std::bit_cast<std::uint32_t>(h.hit.t) == std::bit_cast<std::uint32_t>(single->hit.t);
    }
    ++ties;
    const auto ulps = std::abs(std::bit_cast<std::int32_t>(h.hit.t) - std::bit_cast<std::int32_t>(single->hit.t));
    const rt::TriangleVerts& t = tris_[h.triangle];
    const auto again = rt::intersectTriangle(ray, t.p0, t.p1, t.p2);
    return ulps <= 2 && again && again->t == h.hit.t;
  }

  const rt::Bvh& bvh_;
  const std::vector<rt::TriangleVerts>& tris_;
  int rays_ = 0;
};

// The eight rays of a 4 x 2 block of a pinhole camera's pixels at (px, py), looking
// from `eye` toward `target`, 256 x 256 pixels over a 60 degree field.
std::array<rt::Ray<float>, 8> cameraPacket(const glm::vec3& eye, const glm::vec3& target, int px, int py) {
  const glm::vec3 forward = glm::normalize(target - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  std::array<rt::Ray<float>, 8> rays;
  for (int i = 0; i < 8; ++i) {
    const float u = (float(px + i % 4) + 0.5f) / 128.0f - 1.0f, v = (float(py + i / 4) + 0.5f) / 128.0f - 1.0f;
    rays[std::size_t(i)] = rt::Ray<float>{eye, forward + 0.577f * (u * right + v * up)};
  }
  return rays;
}

void checkScene(const std::vector<rt::TriangleVerts>& tris, std::uint32_t seed, PacketCheck& check) {
  rt::Bvh bvh;
  bvh.build(tris);
  PacketCheck local(bvh, tris);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-14.0f, 14.0f), unit(0.0f, 1.0f);
  for (int view = 0; view < 24; ++view) {
    const glm::vec3 eye(pos(rng), pos(rng), pos(rng)), target(0.3f * pos(rng), 0.3f * pos(rng), 0.3f * pos(rng));
    for (int py = 0; py < 256; py += 2 * 8) {
      for (int px = 0; px < 256; px += 4 * 4) {
        std::array<rt::Ray<float>, 8> rays = cameraPacket(eye, target, px, py);
        local.check(rays);
        // Origins spread over a small box, and a tMax per lane: none, random, or
        // exactly the single ray's hit (which must then miss: tMax is exclusive).
        for (auto& r : rays) {
          r.o += glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.05f;
          const float kind = unit(rng);
          if (kind < 0.3f) r.tMax = 1.0f + 30.0f * unit(rng);
          if (const auto hit = bvh.intersect(r); hit && kind > 0.7f) r.tMax = hit->hit.t;
        }
        local.check(rays);
      }
    }
  }
  // Incoherent packets: traced one ray at a time, the same answers.
  for (int i = 0; i < 200; ++i) {
    std::array<rt::Ray<float>, 8> rays;
    for (auto& r : rays) r = rt::Ray<float>{glm::vec3(pos(rng), pos(rng), pos(rng)), glm::vec3(pos(rng), pos(rng), pos(rng))};
    local.check(rays);
  }
  check.packets += local.packets;
  check.oneByOne += local.oneByOne;
  check.mismatches += local.mismatches;
  check.ties += local.ties;
  check.hitCount += local.hitCount;
  check.boundary += local.boundary;
}

// Each compile of the packet traversal this CPU runs: AVX2, and AVX2 with AVX-512VL's
// registers.
template <typename Check>
void forEachPacketIsa(Check check) {
  forEachIsa({rt::Bvh::Isa::kAvx2, rt::Bvh::Isa::kAvx512}, check);
}

TEST(BvhPacket, EightRaysTogetherAnswerAsOneByOne) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the packet traversal needs AVX2";
  forEachPacketIsa([] {
    std::vector<rt::TriangleVerts> none;
    rt::Bvh dummy;
    PacketCheck total(dummy, none);
    std::mt19937 rng(7);
    checkScene(soupOf(6000, rng), 1, total);
    checkScene(gridOf(64, 0.4f, [](float x, float z) { return 2.0f * std::sin(0.5f * x) * std::cos(0.4f * z); }), 2, total);
    checkScene(gridOf(32, 0.5f, [](float, float) { return 0.0f; }), 3, total);
    EXPECT_EQ(total.mismatches, 0) << total.hitCount << " hits, " << total.ties << " ties, " << total.boundary
                                    << " at tMax, " << total.packets << " packets, " << total.oneByOne << " one by one";
    // The packet path must have done most of the work, and incoherent packets none.
    EXPECT_GT(total.packets, 5 * total.oneByOne / 2);
    EXPECT_GE(total.oneByOne, 600);
    EXPECT_GT(total.hitCount, 100000);
  });
}

// A flat grid, eight rays from one point aimed at consecutive vertices, edge midpoints
// and quad centres: no ray may slip between two triangles.
TEST(BvhPacket, RaysAtSharedEdgesAndVerticesNeverSlipThrough) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the packet traversal needs AVX2";
  forEachPacketIsa([] {
    const auto tris = gridOf(16, 1.0f, [](float, float) { return 0.0f; });
    rt::Bvh bvh;
    bvh.build(tris);
    PacketCheck check(bvh, tris);
    int missed = 0;
    for (const glm::vec3 origin : {glm::vec3(0.1f, 9.0f, 0.2f), glm::vec3(-3.0f, 4.0f, 2.0f), glm::vec3(5.0f, 2.5f, -6.0f)}) {
      for (int z = 1; z < 32; ++z) {
        for (int x = 1; x + 8 <= 32; x += 8) {
          std::array<rt::Ray<float>, 8> rays;
          for (int i = 0; i < 8; ++i) {
            const glm::vec3 target(0.5f * float(x + i) - 8.0f, 0.0f, 0.5f * float(z) - 8.0f);
            rays[std::size_t(i)] = rt::Ray<float>{origin, target - origin};
          }
          std::array<rt::BvhHit<float>, 8> hits{};
          missed += 8 - std::popcount(bvh.intersect8(rays, hits));
          check.check(rays);
        }
      }
    }
    EXPECT_EQ(missed, 0);
    EXPECT_EQ(check.mismatches, 0);
    EXPECT_GT(check.packets, check.oneByOne);
  });
}

}  // namespace
