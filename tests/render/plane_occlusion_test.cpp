// Occlusion by opaque planes (render/plane_occlusion.h) against brute force: every
// box it calls hidden is hidden at every pixel its points reach, with the margins
// it promises, under both depth conventions; and what shows is not called hidden.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "render/plane_occlusion.h"

using namespace engine;
using namespace engine::cull;

namespace {

struct Quad {
  glm::dvec3 center{0.0}, u{1, 0, 0}, v{0, 0, 1};  // unit axes in its plane
  double extent = 1.0;                               // half size along each
  std::array<glm::dvec3, 4> corners() const {
    return {center - u * extent - v * extent, center + u * extent - v * extent, center + u * extent + v * extent,
            center - u * extent + v * extent};
  }
};

glm::dmat4 cameraAt(bool reverseZ, double fovy, double aspect, const glm::dvec3& forward) {
  const glm::dvec3 up = std::abs(forward.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dmat4 projection = reverseZ ? glm::perspectiveRH_ZO(fovy, aspect, 500.0, 0.1)
                                         : glm::perspectiveRH_NO(fovy, aspect, 0.1, 500.0);
  return projection * glm::lookAt(glm::dvec3(0.0), forward, up);
}

// Where the ray from the eye through pixel `p` meets the quad's plane, if in front.
std::optional<glm::dvec3> rayOnPlane(const glm::dmat4& viewProjection, glm::dvec2 viewport, glm::dvec2 p,
                                     const ScreenQuad& plane) {
  const glm::dvec2 ndc = p / viewport * 2.0 - 1.0;
  const glm::dvec4 far = glm::inverse(viewProjection) * glm::dvec4(ndc, 0.5, 1.0);
  const glm::dvec3 direction = glm::dvec3(far) / far.w;
  const double along = glm::dot(plane.normal, direction);
  if (!(along < 0.0)) return std::nullopt;
  return direction * (-plane.offset / along);
}

// The quad is what the pixel's ray meets first: inside its sides, before the near
// plane's far side, and the point `x` lies behind it by the promised margin.
void expectHiddenAt(const Quad& quad, const ScreenQuad& screen, const glm::dmat4& viewProjection, glm::dvec2 viewport,
                    const glm::dvec3& x) {
  EXPECT_GE(-(glm::dot(screen.normal, x) + screen.offset), kPlaneDepthMargin * screen.offset);
  const glm::dvec4 clip = viewProjection * glm::dvec4(x, 1.0);
  ASSERT_GT(clip.w, 0.0);
  const glm::dvec2 pixel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * viewport;
  // Pixel centres a little less than the margin away, all around.
  const double reach = kPlanePixelMargin * 0.95;
  for (int k = 0; k <= 8; ++k) {
    const double angle = k * 0.7853981633974483;
    const glm::dvec2 offset = k == 8 ? glm::dvec2(0.0) : reach * glm::dvec2(std::cos(angle), std::sin(angle));
    const auto hit = rayOnPlane(viewProjection, viewport, pixel + offset, screen);
    ASSERT_TRUE(hit.has_value());
    const glm::dvec3 local = *hit - quad.center;
    EXPECT_LE(std::abs(glm::dot(local, quad.u)), quad.extent * (1.0 + 1e-9));
    EXPECT_LE(std::abs(glm::dot(local, quad.v)), quad.extent * (1.0 + 1e-9));
    const glm::dvec4 h = viewProjection * glm::dvec4(*hit, 1.0);
    EXPECT_GE(h.w - h.z, -1e-9 * h.w);  // not before the near plane (either convention)
    EXPECT_GE(h.w + h.z, -1e-9 * h.w);
  }
}

glm::dvec3 unitVector(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
}

}  // namespace

// 40,000 random boxes behind random quads seen by random cameras, both depth
// conventions: each one called hidden is checked at its corners and at 30 random
// points, each at its pixel and at eight points around it nearly the margin away.
TEST(PlaneOcclusion, EveryBoxCalledHiddenIsBehindTheQuadAtEveryPixelItCovers) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int hidden = 0, tested = 0;
  for (int scene = 0; scene < 400; ++scene) {
    const bool reverseZ = scene % 2 == 0;
    const glm::dvec2 viewport(double(160 + rng() % 1200), double(90 + rng() % 700));
    const glm::dvec3 forward = unitVector(rng);
    const glm::dmat4 viewProjection = cameraAt(reverseZ, 0.4 + 1.4 * u01(rng), viewport.x / viewport.y, forward);
    Quad quad;
    const glm::dvec3 normal = unitVector(rng);
    quad.u = glm::normalize(glm::cross(normal, unitVector(rng)));
    quad.v = glm::cross(normal, quad.u);
    quad.extent = 1.0 + 60.0 * u01(rng);
    quad.center = forward * (2.0 + 40.0 * u01(rng)) + unitVector(rng) * (10.0 * u01(rng));
    const auto screen = screenQuad(quad.corners(), viewProjection, viewport);
    if (!screen) continue;
    for (int b = 0; b < 100; ++b) {
      // Behind the plane (from the eye), somewhere over the quad or past it.
      const double side = glm::dot(normal, -quad.center) > 0.0 ? -1.0 : 1.0;
      const glm::dvec3 at = quad.center + quad.u * (quad.extent * (2.4 * u01(rng) - 1.2)) +
                            quad.v * (quad.extent * (2.4 * u01(rng) - 1.2)) + normal * (side * 30.0 * u01(rng));
      const glm::dvec3 half = glm::dvec3(u01(rng), u01(rng), u01(rng)) * (0.1 + 8.0 * u01(rng));
      ++tested;
      if (!hidesBox(*screen, at - half, at + half, viewProjection, viewport)) continue;
      ++hidden;
      for (int i = 0; i < 8; ++i)
        expectHiddenAt(quad, *screen, viewProjection, viewport,
                       at + glm::dvec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1) * half);
      for (int i = 0; i < 30; ++i)
        expectHiddenAt(quad, *screen, viewProjection, viewport,
                       at + (glm::dvec3(u01(rng), u01(rng), u01(rng)) * 2.0 - 1.0) * half);
      if (::testing::Test::HasFailure()) return;
    }
  }
  std::printf("%d of %d boxes hidden\n", hidden, tested);
  EXPECT_GT(hidden, tested / 20);  // not a test of nothing
}

// The plaza's case: the eye 2.6 m over a 70 m ground, a box of terrain under it.
// Hidden deep enough under it; not when it comes within the depth margin of the
// ground, when it reaches past the ground's far edge into view, or when a corner
// lies behind the eye.
TEST(PlaneOcclusion, WhatShowsOrNearlyTouchesIsNotHidden) {
  const glm::dvec2 viewport(1280, 720);
  for (bool reverseZ : {true, false}) {
    const glm::dmat4 viewProjection = cameraAt(reverseZ, 1.0, 1280.0 / 720.0, glm::normalize(glm::dvec3(0, -0.2, -1)));
    Quad ground;
    ground.center = {0, -2.6, -20};
    ground.extent = 35.0;
    const auto screen = screenQuad(ground.corners(), viewProjection, viewport);
    ASSERT_TRUE(screen.has_value());
    EXPECT_NEAR(screen->offset, 2.6, 1e-12);
    const glm::dvec3 lo(-10, -20, -40), hi(10, -3, -20);
    EXPECT_TRUE(hidesBox(*screen, lo, hi, viewProjection, viewport));
    const double touching = -2.6 - 0.5 * kPlaneDepthMargin * 2.6;
    EXPECT_FALSE(hidesBox(*screen, lo, {hi.x, touching, hi.z}, viewProjection, viewport));
    // Past the far edge (z = -55) and up to 1 m under the ground: the sight line
    // over the edge passes above it there, so it shows.
    EXPECT_FALSE(hidesBox(*screen, {-10, -3.6, -70}, {10, -3, -60}, viewProjection, viewport));
    EXPECT_TRUE(hidesBox(*screen, {-10, -40, -70}, {10, -30, -60}, viewProjection, viewport));
    EXPECT_FALSE(hidesBox(*screen, {-10, -20, -40}, {10, -3, 1}, viewProjection, viewport));
  }
}

// No outline when the eye lies in the quad's plane or the quad is behind it.
TEST(PlaneOcclusion, NoOutlineEdgeOnOrBehind) {
  const glm::dmat4 viewProjection = cameraAt(true, 1.0, 1.0, {0, 0, -1});
  Quad edgeOn;
  edgeOn.center = {0, 0, -10};
  EXPECT_FALSE(screenQuad(edgeOn.corners(), viewProjection, {100, 100}).has_value());
  Quad behind;
  behind.center = {0, -1, 10};
  EXPECT_FALSE(screenQuad(behind.corners(), viewProjection, {100, 100}).has_value());
}
