#include "app/camera_controller.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace engine {
namespace {
constexpr double kRadiansPerPixel = 0.005;
constexpr double kPitchLimit = 1.55;  // just short of straight up or down
}  // namespace

void CameraController::attach(const Camera& camera, double distance) {
  distance_ = distance;
  target_ = camera.position + camera.forward() * distance;
  yaw_ = camera.yaw;
  pitch_ = camera.pitch;
}

void CameraController::onScroll(double yOffset) { pendingScroll_ += yOffset; }

void CameraController::toggleMode() { mode_ = mode_ == Mode::Orbit ? Mode::Fly : Mode::Orbit; }

void CameraController::applyOrbit(Camera& camera) const {
  camera.yaw = yaw_;
  camera.pitch = pitch_;
  camera.position = target_ - camera.forward() * distance_;
}

void CameraController::update(GLFWwindow* window, Camera& camera, double dt) {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  const double dx = dragging_ ? x - lastX_ : 0.0, dy = dragging_ ? y - lastY_ : 0.0;
  lastX_ = x;
  lastY_ = y;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  const bool middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  dragging_ = left || right || middle;

  if (mode_ == Mode::Orbit) {
    if (left) {
      yaw_ += dx * kRadiansPerPixel;
      pitch_ = std::clamp(pitch_ - dy * kRadiansPerPixel, -kPitchLimit, kPitchLimit);
    }
    if (middle) {
      const double scale = distance_ * 0.002;
      target_ += (-camera.right() * dx + glm::dvec3(0, 1, 0) * dy) * scale;
    }
    distance_ = std::max(0.05, distance_ * std::pow(0.9, pendingScroll_));
    pendingScroll_ = 0.0;
    applyOrbit(camera);
    return;
  }

  if (right) {
    camera.yaw += dx * kRadiansPerPixel;
    camera.pitch = std::clamp(camera.pitch - dy * kRadiansPerPixel, -kPitchLimit, kPitchLimit);
  }
  const bool fast = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  const double speed = (fast ? 20.0 : 4.0) * dt;
  auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0 : 0.0; };
  camera.position += camera.forward() * speed * (held(GLFW_KEY_W) - held(GLFW_KEY_S));
  camera.position += camera.right() * speed * (held(GLFW_KEY_D) - held(GLFW_KEY_A));
  camera.position.y += speed * (held(GLFW_KEY_E) - held(GLFW_KEY_Q));
  // Keep the orbit state in step, so switching back orbits what is in view.
  yaw_ = camera.yaw;
  pitch_ = camera.pitch;
  target_ = camera.position + camera.forward() * distance_;
}

}  // namespace engine
