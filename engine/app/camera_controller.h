#pragma once
// Mouse and keyboard camera for the window: orbit around a target (left drag
// rotates, wheel zooms, middle drag pans) or fly (right drag looks, WASD/QE move,
// shift is faster). F switches between the two.
#include <glm/glm.hpp>

#include "render/camera.h"

struct GLFWwindow;

namespace engine {

class CameraController {
 public:
  enum class Mode { Orbit, Fly };

  // Starts orbiting the point the camera looks at, `distance` ahead.
  void attach(const Camera& camera, double distance);
  void update(GLFWwindow* window, Camera& camera, double dt);
  void onScroll(double yOffset);
  void toggleMode();
  Mode mode() const { return mode_; }

 private:
  void applyOrbit(Camera& camera) const;

  Mode mode_ = Mode::Orbit;
  glm::dvec3 target_{0.0};
  double distance_ = 5.0;
  double yaw_ = 0.0, pitch_ = 0.0;
  double lastX_ = 0.0, lastY_ = 0.0;
  bool dragging_ = false;
  double pendingScroll_ = 0.0;
};

}  // namespace engine
