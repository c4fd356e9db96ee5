#include "render/mesh.h"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <span>

namespace engine {

GpuMesh::GpuMesh(const ShapeData& data)
    : vertices_(gl::Buffer::fromSpan(std::span<const Vertex>(data.vertices))),
      indices_(gl::Buffer::fromSpan(std::span<const std::uint32_t>(data.indices))),
      vao_(gl::VertexArray::create()),
      indexCount_(static_cast<GLsizei>(data.indices.size())) {
  vao_.vertexBuffer(0, vertices_, sizeof(Vertex));
  vao_.indexBuffer(indices_);
  vao_.attribute(kPositionLocation, 0, 3, offsetof(Vertex, position));
  vao_.attribute(kNormalLocation, 0, 3, offsetof(Vertex, normal));
  vao_.attribute(kUvLocation, 0, 2, offsetof(Vertex, uv));
  std::vector<glm::vec3> positions;
  for (const Vertex& v : data.vertices) positions.push_back(v.position);
  clusterRange_ = cull::appendClusters(positions, data.indices, 0, std::uint32_t(data.indices.size()), clusters_);
}

void GpuMesh::draw() const {
  vao_.bind();
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace engine

namespace engine {

void GpuMesh::drawIndirect(GLintptr offset, GLsizei count) const {
  vao_.bind();
  glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, reinterpret_cast<const void*>(offset), count, 0);
}

}  // namespace engine
