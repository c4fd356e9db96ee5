#include "render/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace engine {

glm::dvec3 Camera::forward() const {
  const double cp = std::cos(pitch);
  return {std::sin(yaw) * cp, std::sin(pitch), -std::cos(yaw) * cp};
}

glm::dvec3 Camera::right() const { return {std::cos(yaw), 0.0, std::sin(yaw)}; }

void Camera::lookAt(const glm::dvec3& target) {
  const glm::dvec3 d = glm::normalize(target - position);
  pitch = std::asin(glm::clamp(d.y, -1.0, 1.0));
  yaw = std::atan2(d.x, -d.z);
}

glm::mat4 Camera::rotationView() const {
  return glm::mat4(glm::lookAt(glm::dvec3(0.0), forward(), glm::dvec3(0.0, 1.0, 0.0)));
}

glm::mat4 Camera::projection(double aspect) const {
  return glm::mat4(glm::perspective(glm::radians(fovyDegrees), aspect, nearPlane, farPlane));
}

}  // namespace engine
