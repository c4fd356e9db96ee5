#pragma once
// Triangle lists drawn in runs (asset/vertex_runs.h): glTF primitives
// (render/model_renderer.h) and the analytic shapes (render/mesh.h). A vertex array
// binds the runs' 16-bit indices; the draws that are not in runs (levels of detail,
// GPU culling's commands) bind the 32-bit ones into the same copies for their draw.
#include <span>

#include "asset/vertex_runs.h"
#include "gl/resources.h"

namespace engine {

// Draws `runs` from the bound vertex array's 16-bit run indices.
void drawRuns(std::span<const VertexRun> runs, GLenum mode);

// Runs `draw` with `whole` bound as the bound vertex array's indices, then `runs` again.
template <typename Draw>
void withWholeIndices(const gl::Buffer& whole, const gl::Buffer& runs, Draw draw) {
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, whole.id());
  draw();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, runs.id());
}

}  // namespace engine
