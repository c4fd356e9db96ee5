#include "render/mesh.h"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <span>

#include "render/run_draws.h"

namespace engine {

namespace {

// A shape's triangles in runs (asset/vertex_runs.h), in the order they are made.
RunSplit runsOf(const ShapeData& data) { return splitIntoRuns(data.indices, data.vertices.size()); }

}  // namespace

GpuMesh::GpuMesh(const ShapeData& data) : GpuMesh(data, runsOf(data)) {}

GpuMesh::GpuMesh(const ShapeData& data, const RunSplit& split)
    : vertices_(gl::Buffer::fromSpan(std::span<const Vertex>(inSplitOrder(data.vertices, split)))),
      runIndices_(gl::Buffer::fromSpan(std::span<const std::uint16_t>(runIndexBuffer(split)))),
      vao_(gl::VertexArray::create()),
      indexCount_(static_cast<GLsizei>(data.indices.size())),
      runs_(split.runs) {
  const std::vector<std::uint32_t> whole = indicesIntoCopies(split);
  indices_ = gl::Buffer::fromSpan(std::span<const std::uint32_t>(whole));
  vao_.vertexBuffer(0, vertices_, sizeof(Vertex));
  vao_.indexBuffer(runIndices_);
  vao_.attribute(kPositionLocation, 0, 3, offsetof(Vertex, position));
  vao_.attribute(kNormalLocation, 0, 3, offsetof(Vertex, normal));
  vao_.attribute(kUvLocation, 0, 2, offsetof(Vertex, uv));
  std::vector<glm::vec3> positions;
  for (const std::uint32_t v : split.sourceVertex) positions.push_back(data.vertices[v].position);
  clusterRange_ = cull::appendClusters(positions, whole, 0, std::uint32_t(indexCount_), clusters_);
}

void GpuMesh::draw() const {
  vao_.bind();
  drawRuns(runs_, GL_TRIANGLES);
}

}  // namespace engine

namespace engine {

void GpuMesh::drawIndirect(GLintptr offset, GLsizei count) const {
  vao_.bind();
  withWholeIndices(indices_, runIndices_, [&] {
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, reinterpret_cast<const void*>(offset), count, 0);
  });
}

}  // namespace engine
