#pragma once
// The three implementations of GlContext; only gl_context.cpp calls these.
#include <memory>

#include "platform/gl_context.h"

namespace engine {

Result<std::unique_ptr<GlContext>> createGlfwContext(const ContextOptions& options);
Result<std::unique_ptr<GlContext>> createEglContext(const ContextOptions& options);
Result<std::unique_ptr<GlContext>> createOsMesaContext(const ContextOptions& options);

// For the sanitizer runs only (scripts/test --sanitize sets ENGINE_KEEP_GL_DRIVER to
// Mesa's swrast_dri.so): EGL and GLX dlopen that driver and dlclose it on
// terminate, and LeakSanitizer then reports the driver's leftovers at exit against
// an unmapped address, with no library name for tests/sanitizers/lsan.supp to match.
// Opened here first with RTLD_NODELETE, it stays mapped. Called before a display is
// opened; does nothing when the variable is unset. (It used to be LD_PRELOADed
// into every test process, GL or not: 0.18 s each under ASan.)
void keepGlDriverMapped();

// GlContext::loadGl is protected; the backends reach it through this friend-free
// hook so that the interface stays small.
class BackendContext : public GlContext {
 protected:
  using GlContext::loadGl;
};

}  // namespace engine
