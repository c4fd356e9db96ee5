// A GLFW window with a GL 4.5 core context. GLFW loads libGL/libEGL itself at run
// time; we never link -lGL, and load GL through glfwGetProcAddress.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "platform/gl_context_impl.h"

namespace engine {
namespace {

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown error";
}

void* glfwProc(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

// GLFW is process-wide, and so is its display connection: glfwInit opens it and
// glfwTerminate closes it. The display probe and the window share one
// initialisation, kept until the process exits: a bare X server (Xvfb with no other
// client) resets when its last client disconnects, so a probe that closed its
// connection before the window opened another found the server gone half the time
// on busy machines. Windows come and go; the connection stays.
// Why glfwInit failed, kept for every later caller (GLFW reports an error once).
std::string gInitError;

bool glfwReady() {
  static const bool ready = [] {
    keepGlDriverMapped();
    if (!glfwInit()) {
      gInitError = lastGlfwError();
      return false;
    }
    std::atexit(glfwTerminate);
    return true;
  }();
  return ready;
}

class GlfwContext final : public BackendContext {
 public:
  ~GlfwContext() override {
    if (window_) glfwDestroyWindow(window_);
  }
  Backend backend() const override { return Backend::Window; }
  void makeCurrent() override { glfwMakeContextCurrent(window_); }
  void swapBuffers() override { glfwSwapBuffers(window_); }
  GLFWwindow* window() override { return window_; }

  Status init(const ContextOptions& options) {
    if (!glfwReady()) {
      return makeError("window: no usable display (" + gInitError +
                       "); use --offscreen to render without one");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
      return makeError("window: cannot open a window with OpenGL 4.5 core (" + lastGlfwError() +
                       "); use --offscreen to render without one");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(options.vsync ? 1 : 0);
    return loadGl(glfwProc, "window");
  }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createGlfwContext(const ContextOptions& options) {
  auto context = std::make_unique<GlfwContext>();
  if (auto status = context->init(options); !status) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

bool displayAvailable() {
  // glfwInit succeeds only when it can reach a display server; a hidden 1x1
  // window with our context settings is the real test. The connection stays open
  // for the window that follows (see glfwReady).
  if (!glfwReady()) return false;
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWwindow* probe = glfwCreateWindow(1, 1, "probe", nullptr, nullptr);
  const bool ok = probe != nullptr;
  if (probe) glfwDestroyWindow(probe);
  glfwDefaultWindowHints();
  return ok;
}

}  // namespace engine
