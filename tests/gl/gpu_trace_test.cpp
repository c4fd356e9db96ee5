// The GPU tracer (engine/gputrace, shaders/rt/) against its CPU twin, through EGL and
// OSMesa: ray queries on the flattened BVH8 find the CPU BVH's closest hits and any
// hits, and the Whitted integrator renders the CPU's image of the course room.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "../support/gl_test.h"
#include "../support/rt_queries.h"
#include "asset/scene_file.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/integrator.h"

using namespace engine;
using engine::test::GlTest;

namespace {

rt::RtScene cornell() {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  EXPECT_TRUE(desc) << desc.error().message;
  auto scene = rt::RtScene::fromSceneDesc(*desc);
  EXPECT_TRUE(scene) << scene.error().message;
  return std::move(scene).value();
}

std::vector<gpurt::RayQuery> queriesOf(const std::vector<rt::Ray<float>>& rays) {
  std::vector<gpurt::RayQuery> out;
  for (const rt::Ray<float>& r : rays) out.push_back(gpurt::RayQuery{glm::vec4(r.o, r.tMax), glm::vec4(r.d, 0.0f)});
  return out;
}

// The GPU's t may differ from the CPU's by its own rounding of division and square
// root (GLSL allows 2.5 ulps for a division, more for sqrt), through a few
// operations: 1e-5 relative is some 80 ulps, far below any distance between two
// different surfaces a ray could hit instead, which would show as a different id.
constexpr float kRelativeT = 1e-5f;

struct Agreement {
  int rays = 0, hits = 0, mismatches = 0, anyMismatches = 0, ties = 0;
  float worstT = 0.0f;
};

Agreement compare(const rt::RtScene& scene, const std::vector<rt::Ray<float>>& rays) {
  const rt::GpuSceneLayout layout = rt::flattenScene(scene);
  auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir());
  EXPECT_TRUE(tracer) << tracer.error().message;
  if (!tracer) return {};
  const std::vector<gpurt::RayAnswer> answers = tracer->trace(queriesOf(rays));
  Agreement a;
  a.rays = int(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const test::ReferenceHit cpu = test::cpuClosestHit(scene, layout, rays[i]);
    const gpurt::RayAnswer& gpu = answers[i];
    a.hits += cpu.kind != 0 ? 1 : 0;
    if (bool(gpu.anyHit) != scene.intersectAny(rays[i])) ++a.anyMismatches;
    if (int(gpu.kind) != cpu.kind) {
      ++a.mismatches;
      continue;
    }
    if (cpu.kind == 0) continue;
    const float error = std::abs(gpu.t - cpu.t) / cpu.t;
    a.worstT = std::max(a.worstT, error);
    // Two triangles meeting where the ray hits: either may win (gpu_layout_test.cpp).
    const bool tie = cpu.kind == 3 && gpu.index != cpu.index && error <= kRelativeT;
    a.ties += tie ? 1 : 0;
    if (error > kRelativeT || (gpu.index != cpu.index && !tie)) ++a.mismatches;
  }
  return a;
}

class GpuTrace : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuTrace);

TEST_P(GpuTrace, HitsEqualTheCpuBvhsOnAMeshScene) {
  const rt::RtScene scene = test::meshScene();
  const Agreement a = compare(scene, test::queryRays(4000, 7.0f, 9));
  EXPECT_EQ(a.mismatches, 0) << "of " << a.rays;
  EXPECT_EQ(a.anyMismatches, 0);
  EXPECT_GT(a.hits, a.rays / 2);
  std::printf("gpu trace, mesh scene: %d rays, %d hits, %d ties at shared edges, worst relative t %.3g\n", a.rays, a.hits,
              a.ties, double(a.worstT));
}

// The course room: spheres and planes, rays from inside it in every direction.
TEST_P(GpuTrace, HitsEqualTheCpusInTheCornellRoom) {
  const rt::RtScene scene = cornell();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> x(-2.4f, 2.4f), y(0.1f, 2.9f), z(-2.9f, 4.9f), dir(-1.0f, 1.0f);
  std::vector<rt::Ray<float>> rays;
  for (int i = 0; i < 4000; ++i) rays.push_back(rt::Ray<float>{{x(rng), y(rng), z(rng)}, {dir(rng), dir(rng), dir(rng)}});
  const Agreement a = compare(scene, rays);
  EXPECT_EQ(a.mismatches, 0) << "of " << a.rays;
  EXPECT_EQ(a.anyMismatches, 0);
  std::printf("gpu trace, cornell: %d rays, %d hits, worst relative t %.3g\n", a.rays, a.hits, double(a.worstT));
}

}  // namespace
