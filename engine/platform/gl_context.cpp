#include "platform/gl_context.h"

#include <dlfcn.h>
#include <glad/gl.h>

#include <cstdlib>

#include "gl/object.h"
#include "platform/gl_context_impl.h"

namespace engine {

std::string_view backendName(Backend backend) {
  switch (backend) {
    case Backend::Window: return "window";
    case Backend::Egl: return "egl";
    case Backend::OsMesa: return "osmesa";
  }
  return "?";
}

std::optional<Backend> parseBackend(std::string_view name) {
  if (name == "egl") return Backend::Egl;
  if (name == "osmesa") return Backend::OsMesa;
  if (name == "window" || name == "glfw") return Backend::Window;
  return std::nullopt;
}

// Counted for the GL objects' tripwire (gl/object.h). The backend's destructor,
// which runs first, has destroyed the context by the time the count drops.
GlContext::GlContext() { ++gl::detail::contextsAlive; }
GlContext::~GlContext() { --gl::detail::contextsAlive; }

namespace {
// glad wants a function of the GL type; the backends hand out void*.
void* (*gGetProc)(const char*) = nullptr;
GLADapiproc loadProc(const char* name) {
  return reinterpret_cast<GLADapiproc>(gGetProc(name));
}
}  // namespace

Status GlContext::loadGl(void* (*getProc)(const char*), std::string_view backendLabel) {
  // gladLoaderLoadGL() would dlopen libGL, which is wrong under OSMesa; we always
  // load through the backend's own GetProcAddress.
  gGetProc = getProc;
  const int version = gladLoadGL(loadProc);
  if (version == 0) {
    return makeError(std::string(backendLabel) + ": could not load the GL entry points");
  }
  const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
  if (major < 4 || (major == 4 && minor < 5)) {
    return makeError(std::string(backendLabel) + ": OpenGL 4.5 core is needed, got " +
                     std::to_string(major) + "." + std::to_string(minor) +
                     " (on Mesa, try LIBGL_ALWAYS_SOFTWARE=1)");
  }
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return Ok{};
}

void keepGlDriverMapped() {
  static const bool kept = [] {
    const char* path = std::getenv("ENGINE_KEEP_GL_DRIVER");
    return path && *path && dlopen(path, RTLD_NOW | RTLD_NODELETE) != nullptr;
  }();
  (void)kept;
}

Result<std::unique_ptr<GlContext>> createContext(Backend backend, const ContextOptions& options) {
  switch (backend) {
    case Backend::Window: return createGlfwContext(options);
    case Backend::Egl: return createEglContext(options);
    case Backend::OsMesa: return createOsMesaContext(options);
  }
  return makeError("unknown backend");
}

}  // namespace engine
