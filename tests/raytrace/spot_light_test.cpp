// Spot lights (KHR_lights_punctual's cone, shaders/common/spot_cone.glsl) in the CPU
// tracers, against answers known in closed form: a white floor under a spot straight
// above it, seen from above. The Whitted tracer's floor is the course's diffuse term
// of a point light times the Sample Viewer's cone weight, computed here in double
// from the angle; the path tracer's is its own image of the point light inside the
// inner cone, to the bit, and black outside the outer one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "raytrace/camera.h"
#include "raytrace/describe.h"
#include "raytrace/integrator.h"
#include "test_scenes.h"

namespace {

constexpr int kSide = 64;
constexpr double kHeight = 3.0, kInner = 20.0, kOuter = 40.0;
constexpr float kIntensity = 4.0f;

CameraDesc aboveTheFloor() { return lookAt({0.0, 5.0, 0.0}, {0.0, 0.0, 0.0}, 90.0); }

// The white floor (albedo 0.5, diffuse 1, no ambient) under a light at (0, 3, 0)
// with 1/d^2 falloff: a spot shining straight down with cones of 20 and 40 degrees,
// or (`spot` false) the same point light without them.
rt::RtScene floorUnder(bool spot) {
  rt::RtScene scene = emptyScene(aboveTheFloor());
  scene.addPlane({0, 0, 0}, {0, 1, 0}, scene.addMaterial(classic(glm::vec3(0.5f), 0.0f, 1.0f)));
  LightDesc light = pointLight({0.0, kHeight, 0.0});
  light.falloff = true;
  light.intensity = kIntensity;
  if (spot) {
    light.type = LightType::Spot;
    light.direction = {0.0, 1.0, 0.0};  // toward the light: it shines down
    light.innerConeDegrees = float(kInner);
    light.outerConeDegrees = float(kOuter);
  }
  scene.addLight(light);
  return scene;
}

// Where the ray through image point (px, py) meets the floor y = 0.
glm::dvec3 floorPoint(double px, double py) {
  const rt::PinholeCamera camera(aboveTheFloor(), kSide, kSide);
  const auto ray = camera.generateRay<double>(px, py);
  return ray.o + (-ray.o.y / ray.d.y) * ray.d;
}

// The Sample Viewer's cone weight at floor point p, from the angle off the axis.
double coneWeight(const glm::dvec3& p) {
  const double angle = std::atan2(std::hypot(p.x, p.z), kHeight) * 180.0 / 3.14159265358979323846;
  if (angle >= kOuter) return 0.0;
  if (angle <= kInner) return 1.0;
  const double t = (std::cos(angle * 3.14159265358979323846 / 180.0) - std::cos(kOuter * 3.14159265358979323846 / 180.0)) /
                   (std::cos(kInner * 3.14159265358979323846 / 180.0) - std::cos(kOuter * 3.14159265358979323846 / 180.0));
  return t * t;
}

rt::RenderSettings settings(rt::Method method, int spp) {
  rt::RenderSettings s;
  s.method = method;
  s.width = kSide;
  s.height = kSide;
  s.samplesPerPixel = spp;
  s.maxDepth = 4;
  return s;
}

// One ray a pixel, at its centre: the floor's linear colour there is 0.5 cos(theta)
// I / d^2 times the cone's weight, to float's rounding (relative 1e-5 of the point
// light's value, which is at most 0.23 here; measured 6e-7), every pixel of the floor. The floor
// holds all three regions: full light, the ramp and darkness.
TEST(SpotLight, TheWhittedFloorIsThePointLightTimesTheConesWeight) {
  const rt::RtScene scene = floorUnder(true);
  const rt::RenderResult r = rt::Integrator(scene, settings(rt::Method::Whitted, 1)).render();
  int full = 0, ramp = 0, dark = 0;
  double worst = 0.0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const glm::dvec3 p = floorPoint(x + 0.5, y + 0.5);
      const glm::dvec3 toLight = glm::dvec3(0.0, kHeight, 0.0) - p;
      const double d2 = glm::dot(toLight, toLight);
      const double point = 0.5 * (kHeight / std::sqrt(d2)) * kIntensity / d2;
      const double w = coneWeight(p);
      const double expected = point * w;
      full += w == 1.0 ? 1 : 0;
      dark += w == 0.0 ? 1 : 0;
      ramp += w > 0.0 && w < 1.0 ? 1 : 0;
      const glm::vec3 c = r.image.pixels[std::size_t(y) * kSide + std::size_t(x)];
      const double error = std::abs(double(c.x) - expected) / point;
      worst = std::max(worst, error);
      ASSERT_LE(error, 1e-5) << "pixel " << x << ", " << y << ": " << c.x << ", expected " << expected << " (weight " << w << ")";
    }
  }
  std::printf("whitted spot: %d pixels in full light, %d on the ramp, %d dark; worst error %.3g of the point's value\n", full,
              ramp, dark, worst);
  EXPECT_GT(full, 80);
  EXPECT_GT(ramp, 400);
  EXPECT_GT(dark, 400);
  // Outside the cone no shadow ray is traced: one per lit pixel (give or take the
  // pixels on the outer edge, where float and double may disagree).
  EXPECT_NEAR(double(r.rays.shadow), double(full + ramp), 4.0);
}

// The path tracer, 4 samples a pixel from the same random streams: the floor's
// light arrives only from the light (its bounces escape to the black background), so
// a pixel whose every sample lies within the inner cone is the point light's pixel
// to the bit, one whose every sample lies beyond the outer cone is black, and one on
// the ramp is between the two. A pixel's samples lie within half a pixel's
// footprint on the floor (at most 0.12 m here) of its centre.
TEST(SpotLight, ThePathTracersSpotIsItsPointLightWithinTheInnerConeAndDarkOutside) {
  const rt::RenderResult spot = rt::Integrator(floorUnder(true), settings(rt::Method::Path, 4)).render();
  const rt::RenderResult point = rt::Integrator(floorUnder(false), settings(rt::Method::Path, 4)).render();
  const double innerRadius = kHeight * std::tan(kInner * 3.14159265358979323846 / 180.0);
  const double outerRadius = kHeight * std::tan(kOuter * 3.14159265358979323846 / 180.0);
  int full = 0, ramp = 0, dark = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const glm::dvec3 p = floorPoint(x + 0.5, y + 0.5);
      const double r = std::hypot(p.x, p.z);
      const double reach = glm::distance(floorPoint(x, y), floorPoint(x + 1, y + 1));
      const std::size_t i = std::size_t(y) * kSide + std::size_t(x);
      const glm::vec3 s = spot.image.pixels[i], q = point.image.pixels[i];
      if (r + reach < innerRadius) {
        ++full;
        ASSERT_EQ(s, q) << "pixel " << x << ", " << y;
      } else if (r - reach > outerRadius) {
        ++dark;
        ASSERT_EQ(s, glm::vec3(0.0f)) << "pixel " << x << ", " << y;
      } else if (r - reach > innerRadius && r + reach < outerRadius) {
        ++ramp;
        ASSERT_GT(s.x, 0.0f) << "pixel " << x << ", " << y;
        ASSERT_LT(s.x, q.x) << "pixel " << x << ", " << y;
      }
    }
  }
  std::printf("path spot: %d pixels checked in full light, %d on the ramp, %d dark\n", full, ramp, dark);
  EXPECT_GT(full, 80);
  EXPECT_GT(ramp, 200);
  EXPECT_GT(dark, 400);
}

TEST(SpotLight, DescribeCountsTheSpots) {
  const std::string text = rt::describe(floorUnder(true), settings(rt::Method::Whitted, 1));
  EXPECT_NE(text.find("lights: 0 sun, 0 point, 1 spot, 0 area (1 casting shadows)"), std::string::npos) << text;
}

}  // namespace
