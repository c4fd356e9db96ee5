#pragma once
// The three implementations of GlContext; only gl_context.cpp calls these.
#include <memory>

#include "platform/gl_context.h"

namespace engine {

Result<std::unique_ptr<GlContext>> createGlfwContext(const ContextOptions& options);
Result<std::unique_ptr<GlContext>> createEglContext(const ContextOptions& options);
Result<std::unique_ptr<GlContext>> createOsMesaContext(const ContextOptions& options);

// GlContext::loadGl is protected; the backends reach it through this friend-free
// hook so that the interface stays small.
class BackendContext : public GlContext {
 protected:
  using GlContext::loadGl;
};

}  // namespace engine
