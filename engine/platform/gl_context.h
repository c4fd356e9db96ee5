#pragma once
// One interface for the three ways we get a GL 4.5 core context: a GLFW window, EGL
// surfaceless (no display needed) and OSMesa. The renderer never creates a context
// (Filament's habit): the platform hands it one, and all GL functions are loaded
// through glad with the chosen backend's GetProcAddress, so one binary holds all three.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.h"

struct GLFWwindow;

namespace engine {

enum class Backend { Window, Egl, OsMesa };

std::string_view backendName(Backend backend);
// "egl" | "osmesa" | "window"; nullopt for anything else.
std::optional<Backend> parseBackend(std::string_view name);

struct ContextOptions {
  int width = 1280;
  int height = 720;
  std::string title = "demo";
  bool vsync = true;
  // KHR_debug output: on in debug builds and tests, off in release frames.
  bool debug = false;
};

class GlContext {
 public:
  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  virtual Backend backend() const = 0;
  virtual void makeCurrent() = 0;
  // Presents the default framebuffer; a no-op offscreen.
  virtual void swapBuffers() {}
  // The GLFW window when there is one (input, title, resize); null offscreen.
  virtual GLFWwindow* window() { return nullptr; }

  // GL_RENDERER and GL_VERSION strings, read once after loading.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }

 protected:
  GlContext();
  // Loads every GL entry point through `getProc` and checks the version; each
  // backend calls it once its context is current.
  Status loadGl(void* (*getProc)(const char*), std::string_view backendLabel);

 private:
  std::string renderer_;
  std::string version_;
};

// Creates and makes current a context of the given backend, GL loaded. The error
// says which backend, what failed and what to try instead.
Result<std::unique_ptr<GlContext>> createContext(Backend backend, const ContextOptions& options);

// True when a GLFW window could be opened here (a display is usable).
bool displayAvailable();

}  // namespace engine
