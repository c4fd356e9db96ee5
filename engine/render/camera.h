#pragma once
// A perspective camera: position, orientation as yaw/pitch, vertical field of view.
// The projection follows the course: yScale = 1 / tan(fovy / 2) on the y axis and
// xScale = yScale / aspect (GL's form of the same pinhole).
#include <glm/glm.hpp>

namespace engine {

struct Camera {
  glm::dvec3 position{0.0, 2.0, 6.0};  // double: worlds may be far from the origin
  double yaw = 0.0;    // radians, 0 looks along -z, positive turns toward +x... (right-handed, y up)
  double pitch = 0.0;  // radians, positive looks up
  double fovyDegrees = 60.0;
  double nearPlane = 0.1;
  double farPlane = 500.0;

  glm::dvec3 forward() const;
  glm::dvec3 right() const;
  // Points the camera at `target` from where it stands.
  void lookAt(const glm::dvec3& target);
  // View matrix for camera-relative rendering: rotation only; callers subtract the
  // camera position from world positions in double before converting to float.
  glm::mat4 rotationView() const;
  glm::mat4 projection(double aspect) const;
};

}  // namespace engine
