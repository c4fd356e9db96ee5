#pragma once
// The pinhole camera, building rays exactly as the course does: for pixel (x, y) of a
// W x H image, X = (2 (x + 0.5) / W - 1) xScale, Y = -(2 (y + 0.5) / H - 1) yScale,
// Z = 1, with yScale = tan(fovy / 2) and xScale = yScale W / H; the direction is
// normalised and rotated into the camera's basis (right, up, forward). Other sample
// positions inside the pixel replace the 0.5s.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "raytrace/ray.h"

namespace engine::rt {

class PinholeCamera {
 public:
  PinholeCamera(const CameraDesc& camera, int width, int height)
      : position_(camera.position), forward_(glm::normalize(camera.forward)), right_(camera.right()),
        farPlane_(camera.farPlane), width_(width), height_(height) {
    // The up vector orthonormalised against forward, as the rasterizer's view matrix.
    up_ = glm::normalize(camera.up - glm::dot(camera.up, forward_) * forward_);
    yScale_ = std::tan(glm::radians(camera.fovyDegrees) * 0.5);
    xScale_ = yScale_ * double(width) / double(height);
  }

  // A ray through the image point (px, py) in pixels: (x + 0.5, y + 0.5) is the
  // centre of pixel (x, y). Formed in double, then rounded once to T.
  template <typename T>
  Ray<T> generateRay(double px, double py) const {
    const double x = (2.0 * px / width_ - 1.0) * xScale_;
    const double y = -(2.0 * py / height_ - 1.0) * yScale_;
    const glm::dvec3 local = glm::normalize(glm::dvec3(x, y, 1.0));
    const glm::dvec3 d = local.x * right_ + local.y * up_ + local.z * forward_;
    return Ray<T>{Vec3<T>(position_), Vec3<T>(d)};
  }

  // The ray stopped at the camera's far plane, where the rasterizer's depth range
  // ends: a view-space depth of farPlane is t = farPlane / (d . forward) along it.
  template <typename T>
  Ray<T> clippedToFarPlane(Ray<T> ray) const {
    const double depthPerT = glm::dot(glm::dvec3(ray.d), forward_);
    if (depthPerT > 0.0) ray.tMax = std::min(ray.tMax, T(farPlane_ / depthPerT));
    return ray;
  }

  const glm::dvec3& position() const { return position_; }
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }
  const glm::dvec3& forward() const { return forward_; }
  // What generateRay and clippedToFarPlane compute with (the packets' own copy of
  // their arithmetic, raytrace/whitted_packets.cpp, reads them here).
  double farPlane() const { return farPlane_; }
  double xScale() const { return xScale_; }
  double yScale() const { return yScale_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  glm::dvec3 position_, forward_, right_, up_{0, 1, 0};
  double farPlane_ = 1000.0;
  int width_, height_;
  double xScale_ = 1.0, yScale_ = 1.0;
};

}  // namespace engine::rt
