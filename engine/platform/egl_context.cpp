// EGL without any window system: Mesa's surfaceless platform, falling back to the
// device platform (drivers such as NVIDIA's expose that one instead). We draw into
// our own framebuffer objects, so no EGL surface is ever made.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>

#include "platform/gl_context_impl.h"

namespace engine {
namespace {

std::string eglErrorText(const char* what) {
  char buf[64];
  std::snprintf(buf, sizeof buf, " (EGL error 0x%04x)", eglGetError());
  return std::string("EGL: ") + what + buf;
}

void* eglProc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

EGLDisplay openDisplay() {
  keepGlDriverMapped();
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) return EGL_NO_DISPLAY;
  EGLDisplay display =
      getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;

  auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!queryDevices) return EGL_NO_DISPLAY;
  EGLDeviceEXT devices[8];
  EGLint count = 0;
  if (!queryDevices(8, devices, &count)) return EGL_NO_DISPLAY;
  for (EGLint i = 0; i < count; ++i) {
    display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  }
  return EGL_NO_DISPLAY;
}

class EglContext final : public BackendContext {
 public:
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
    }
  }
  Backend backend() const override { return Backend::Egl; }
  void makeCurrent() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_); }

  Status init(const ContextOptions& options) {
    display_ = openDisplay();
    if (display_ == EGL_NO_DISPLAY) {
      return makeError(eglErrorText("no surfaceless or device display could be opened") +
                       "; is Mesa's libegl1 installed? try --offscreen=osmesa");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return makeError(eglErrorText("desktop OpenGL is not offered"));
    // The default surface type is "window", which surfaceless displays have none of.
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    if (!eglChooseConfig(display_, configAttribs, &config, 1, &numConfigs) || numConfigs == 0) {
      return makeError(eglErrorText("no config with desktop OpenGL"));
    }
    const EGLint contextAttribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT) {
      return makeError(eglErrorText("cannot create an OpenGL 4.5 core context") +
                       "; try --offscreen=osmesa");
    }
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      return makeError(eglErrorText("cannot make the context current without a surface"));
    }
    return loadGl(eglProc, "EGL");
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createEglContext(const ContextOptions& options) {
  auto context = std::make_unique<EglContext>();
  if (auto status = context->init(options); !status) return status.error();
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace engine
