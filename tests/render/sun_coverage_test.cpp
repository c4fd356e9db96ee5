// Where the sun's near map covers fully (render/sun_coverage.h) against the
// shader's own arithmetic: every box withinNearSunMap accepts gives inside == 1,
// in float as common/shadows.glsl computes it, at random points of the box with
// random unit normals; boxes well inside are accepted and boxes reaching past the
// inner part or the depth range are not.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "render/sun_coverage.h"

using namespace engine;

namespace {

// A sun box as SunShadowPass::fitBox makes it: orthographic, around
// `center` (camera-relative) with `radius`, looking along -l; the float matrix the
// frame block holds.
glm::mat4 sunShadowMatrix(const glm::dvec3& center, double radius, const glm::dvec3& l) {
  const glm::dvec3 up = std::abs(l.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 lx = glm::normalize(glm::cross(up, l)), ly = glm::cross(l, lx);
  const double casterMargin = 200.0;
  const glm::dmat4 view = glm::lookAt(center + l * (radius + casterMargin), center, ly);
  const glm::dmat4 projection = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.0, 2.0 * radius + casterMargin);
  const glm::dmat4 bias = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 0.0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 1.0));
  return glm::mat4(bias * projection * view);
}

// shadows.glsl's `inside`, in float.
float shaderInside(const glm::mat4& shadowMatrix, const glm::vec3& position, const glm::vec3& n, float texelWorld) {
  const glm::vec4 p = shadowMatrix * glm::vec4(position + n * texelWorld * 1.5f, 1.0f);
  const glm::vec3 uvz = glm::vec3(p) / p.w;
  const glm::vec2 edge = glm::min(glm::vec2(uvz), 1.0f - glm::vec2(uvz));
  if (uvz.z < 0.0f || uvz.z > 1.0f) return 0.0f;
  const float e = std::min(edge.x, edge.y);
  const float t = glm::clamp(e / 0.1f, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

TEST(SunCoverage, AcceptedBoxesHaveEveryLookupFullyInside) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), zeroOne(0.0, 1.0);
  int accepted = 0, rejected = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    glm::dvec3 l(unit(rng), 0.05 + zeroOne(rng), unit(rng));
    l = glm::normalize(l);
    const double radius = 5.0 + 200.0 * zeroOne(rng);
    const glm::dvec3 center(unit(rng) * 100.0, unit(rng) * 20.0, unit(rng) * 100.0);
    const glm::mat4 m = sunShadowMatrix(center, radius, l);
    const double texelWorld = 2.0 * radius / 2048.0;
    const glm::dvec3 boxCenter = center + glm::dvec3(unit(rng), unit(rng), unit(rng)) * radius;
    const glm::dvec3 half = glm::dvec3(zeroOne(rng), zeroOne(rng), zeroOne(rng)) * radius * 0.6;
    const glm::dvec3 lo = boxCenter - half, hi = boxCenter + half;
    if (!withinNearSunMap(glm::dmat4(m), lo, hi, texelWorld)) {
      ++rejected;
      continue;
    }
    ++accepted;
    for (int k = 0; k < 200; ++k) {
      // Corners and edges most of all: that is where a bound would leak.
      glm::dvec3 t(zeroOne(rng), zeroOne(rng), zeroOne(rng));
      if (k % 2 == 0) t = glm::round(t);
      const glm::vec3 position(lo + (hi - lo) * t);
      glm::vec3 n(float(unit(rng)), float(unit(rng)), float(unit(rng)));
      if (k % 3 == 0) n = glm::vec3(0.0f);
      n = glm::length(n) > 1e-3f ? glm::normalize(n) : glm::vec3(0, 1, 0);
      if (k % 5 == 0) n = glm::sign(glm::vec3(unit(rng), unit(rng), unit(rng))) * glm::vec3(0.57735f);
      ASSERT_EQ(shaderInside(m, position, n, float(texelWorld)), 1.0f)
          << "trial " << trial << " point " << k << " of an accepted box";
    }
  }
  // Both answers are common in this draw of boxes: the test says something.
  EXPECT_GT(accepted, 2000);
  EXPECT_GT(rejected, 2000);
}

TEST(SunCoverage, TheMapsInnerPartIsAcceptedAndItsEdgeIsNot) {
  const glm::dvec3 l = glm::normalize(glm::dvec3(-0.55, 0.7, -0.25));
  const double radius = 32.0, texelWorld = 2.0 * radius / 2048.0;
  const glm::dmat4 m(sunShadowMatrix(glm::dvec3(0.0), radius, l));
  // A small box at the centre, and one a metre across the map's middle.
  EXPECT_TRUE(withinNearSunMap(m, glm::dvec3(-0.1), glm::dvec3(0.1), texelWorld));
  EXPECT_TRUE(withinNearSunMap(m, glm::dvec3(-0.5), glm::dvec3(0.5), texelWorld));
  // As wide as the map: past its inner 80 %.
  EXPECT_FALSE(withinNearSunMap(m, glm::dvec3(-radius), glm::dvec3(radius), texelWorld));
  // Beyond the depth range, toward and away from the sun.
  EXPECT_FALSE(withinNearSunMap(m, l * (3.0 * radius + 250.0) - 0.1, l * (3.0 * radius + 250.0) + 0.1, texelWorld));
  EXPECT_FALSE(withinNearSunMap(m, -l * (3.0 * radius) - 0.1, -l * (3.0 * radius) + 0.1, texelWorld));
}

}  // namespace
