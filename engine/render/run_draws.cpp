#include "render/run_draws.h"

#include <cstdint>

namespace engine {

void drawRuns(std::span<const VertexRun> runs, GLenum mode) {
  for (const VertexRun& run : runs) {
    glDrawRangeElementsBaseVertex(mode, 0, run.vertexCount - 1, GLsizei(run.indexCount), GL_UNSIGNED_SHORT,
                                  reinterpret_cast<const void*>(std::uintptr_t(run.firstIndex) * sizeof(std::uint16_t)),
                                  GLint(run.firstVertex));
  }
}

}  // namespace engine
