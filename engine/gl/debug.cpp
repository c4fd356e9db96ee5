#include "gl/debug.h"

#include <glad/gl.h>

#include <atomic>
#include <string>

#include "core/log.h"

namespace engine::gl {
namespace {

std::atomic<int> gErrors{0};

void GLAD_API_PTR onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity,
                                 GLsizei length, const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  // Compile and link failures come back through Program::build with file and line;
  // the driver's copy of them is neither news nor a GL error.
  if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
  const std::string text(message, length > 0 ? static_cast<size_t>(length) : std::string(message).size());
  if (type == GL_DEBUG_TYPE_ERROR) {
    ++gErrors;
    logError("GL error " + std::to_string(id) + ": " + text);
  } else {
    logWarning("GL: " + text);
  }
}

}  // namespace

void enableDebugOutput() {
  glEnable(GL_DEBUG_OUTPUT);
  // Synchronous, so the message arrives inside the call that caused it.
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

int errorCount() {
  int pending = 0;
  while (glGetError() != GL_NO_ERROR && pending < 64) ++pending;
  return gErrors.load() + pending;
}

void resetErrorCount() {
  while (glGetError() != GL_NO_ERROR) {
  }
  gErrors = 0;
}

}  // namespace engine::gl
