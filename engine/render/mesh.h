#pragma once
// A triangle mesh's GPU copy; the CPU shapes are scene/shapes.h's.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "gl/resources.h"
#include "scene/shapes.h"

namespace engine {

// Vertex attribute locations shared with shaders/common/vertex.glsl.
inline constexpr GLuint kPositionLocation = 0;
inline constexpr GLuint kNormalLocation = 1;
inline constexpr GLuint kUvLocation = 2;

class GpuMesh {
 public:
  explicit GpuMesh(const ShapeData& data);
  void draw() const;
  GLsizei indexCount() const { return indexCount_; }

 private:
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::VertexArray vao_;
  GLsizei indexCount_ = 0;
};

}  // namespace engine
