#pragma once
// Dear ImGui over a GLFW window: Debian's imgui with its GLFW backend, and the
// OpenGL3 backend compiled here against our glad loader (Debian's own copy would
// load GL by itself, outside the backend's GetProcAddress).
struct GLFWwindow;

namespace engine {

class ImGuiLayer {
 public:
  explicit ImGuiLayer(GLFWwindow* window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  void beginFrame();
  // Draws the panel into the default framebuffer.
  void endFrame(int width, int height);
  bool wantsMouse() const;
};

}  // namespace engine
