// sphereScreenRect scissors the deferred characters' shading: a rect that missed a
// pixel a sphere's contents can reach would leave that pixel of a character
// unshaded. Checked on random views and spheres (points sampled through each
// sphere, those in front of the eye and inside the view must land in the rect),
// with the spheres swept across the eye's plane, where the projection breaks down,
// and against the view's edges; and the rect is tight: no more than the projected
// box and its pixel of margin.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "render/screen_rect.h"

using namespace engine;

namespace {

struct RandomView {
  glm::dmat4 viewProjection;
  int width, height;
};

// A camera-relative reverse-Z view as the scene renderer builds one.
RandomView randomView(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fov(20.0, 120.0);
  std::uniform_int_distribution<int> size(16, 1920);
  glm::dvec3 forward(unit(rng), unit(rng), unit(rng));
  if (glm::length(forward) < 1e-3) forward = glm::dvec3(0, 0, -1);
  const glm::dvec3 up = std::abs(glm::normalize(forward).y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  RandomView v;
  v.width = size(rng);
  v.height = size(rng);
  const glm::dmat4 view = glm::lookAtRH(glm::dvec3(0.0), glm::normalize(forward), up);
  const glm::dmat4 projection =
      glm::perspectiveRH_ZO(glm::radians(fov(rng)), double(v.width) / double(v.height), 1000.0, 0.1);
  v.viewProjection = projection * view;
  return v;
}

// The pixel a camera-relative point falls in, if it is in front of the eye and
// inside the view.
bool pixelOf(const RandomView& v, const glm::dvec3& p, glm::ivec2& pixel) {
  const glm::dvec4 clip = v.viewProjection * glm::dvec4(p, 1.0);
  if (!(clip.w > 0.0)) return false;
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  if (std::abs(ndc.x) >= 1.0 || std::abs(ndc.y) >= 1.0) return false;
  pixel = glm::ivec2(glm::floor((ndc * 0.5 + 0.5) * glm::dvec2(v.width, v.height)));
  return true;
}

// Spheres anywhere around the eye, some straddling its plane, some far: every
// sampled point of each that is drawable lies inside its rect.
TEST(SphereScreenRect, HoldsEveryPixelTheSphereReaches) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), logDistance(-2.0, 3.0), logRadius(-3.0, 1.5);
  long long points = 0, inside = 0;
  for (int sphere = 0; sphere < 50000; ++sphere) {
    const RandomView v = randomView(rng);
    glm::dvec3 direction(unit(rng), unit(rng), unit(rng));
    if (glm::length(direction) < 1e-6) continue;
    const glm::dvec3 center = glm::normalize(direction) * std::pow(10.0, logDistance(rng));
    const double radius = std::pow(10.0, logRadius(rng));
    const glm::ivec4 rect = sphereScreenRect(v.viewProjection, center, radius, v.width, v.height);
    ASSERT_LE(0, rect.x);
    ASSERT_LE(0, rect.y);
    ASSERT_LE(rect.z, v.width);
    ASSERT_LE(rect.w, v.height);
    for (int sample = 0; sample < 64; ++sample) {
      glm::dvec3 offset(unit(rng), unit(rng), unit(rng));
      if (glm::length(offset) > 1.0) continue;  // inside the sphere, its surface included
      if (sample < 16 && glm::length(offset) > 1e-9) offset = glm::normalize(offset);
      glm::ivec2 pixel;
      if (!pixelOf(v, center + offset * radius, pixel)) continue;
      ++points;
      const bool in = pixel.x >= rect.x && pixel.x < rect.z && pixel.y >= rect.y && pixel.y < rect.w;
      inside += in;
      ASSERT_TRUE(in) << "sphere " << sphere << " pixel " << pixel.x << "," << pixel.y << " rect " << rect.x << ","
                      << rect.y << " " << rect.z << "," << rect.w;
    }
  }
  EXPECT_GT(points, 150000);  // the cases do reach the view
  EXPECT_EQ(inside, points);
}

// A sphere that reaches the eye's plane has no bounded image: the whole view.
TEST(SphereScreenRect, TheWholeViewWhereTheSphereReachesTheEyesPlane) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const RandomView v = randomView(rng);
    const glm::dmat4 inverse = glm::inverse(v.viewProjection);
    // A point on the eye's plane (w = 0 there) and a sphere through it.
    glm::dvec4 onPlane = inverse * glm::dvec4(0.3, -0.2, 0.5, 0.0);
    const glm::dvec3 center = glm::dvec3(onPlane) * 1e-3 / std::max(glm::length(glm::dvec3(onPlane)), 1e-30);
    EXPECT_EQ(sphereScreenRect(v.viewProjection, center, 0.01, v.width, v.height),
              glm::ivec4(0, 0, v.width, v.height));
  }
}

// In front and inside the view, the rect is the projected box's pixels and one
// more each way, no larger.
TEST(SphereScreenRect, NoLargerThanTheProjectedBoxAndAPixel) {
  const int width = 1280, height = 720;
  const glm::dmat4 viewProjection =
      glm::perspectiveRH_ZO(glm::radians(45.0), double(width) / height, 100.0, 0.1) *
      glm::lookAtRH(glm::dvec3(0.0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
  // A unit sphere 10 m ahead: the box's nearest face, at 9 m, spans the most.
  const glm::ivec4 rect = sphereScreenRect(viewProjection, glm::dvec3(0, 0, -10), 1.0, width, height);
  const double half = height / 2.0 / std::tan(glm::radians(22.5)) / 9.0;  // pixels a metre at 9 m
  EXPECT_NEAR(rect.z - rect.x, 2.0 * half + 3.0, 2.0);
  EXPECT_NEAR(rect.w - rect.y, 2.0 * half + 3.0, 2.0);
  EXPECT_NEAR((rect.x + rect.z) / 2.0, width / 2.0, 1.0);
}

}  // namespace
