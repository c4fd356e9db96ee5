#pragma once
// A triangle mesh's GPU copy; the CPU shapes are scene/shapes.h's.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "gl/resources.h"
#include "asset/vertex_runs.h"
#include "render/cull_math.h"
#include "scene/shapes.h"

namespace engine {

// Vertex attribute locations shared with shaders/common/vertex.glsl.
inline constexpr GLuint kPositionLocation = 0;
inline constexpr GLuint kNormalLocation = 1;
inline constexpr GLuint kUvLocation = 2;

// Drawn in runs (render/run_draws.h): its buffers hold the runs' copies of the
// shape's vertices.
class GpuMesh {
 public:
  explicit GpuMesh(const ShapeData& data);
  void draw() const;
  // GPU culling's commands for it (render/gpu_cull.h) in the bound
  // GL_DRAW_INDIRECT_BUFFER: `count` commands from byte `offset`.
  void drawIndirect(GLintptr offset, GLsizei count) const;
  GLsizei indexCount() const { return indexCount_; }
  const std::vector<VertexRun>& runs() const { return runs_; }
  // Its indices in runs of at most 128 triangles with their bounds, then the whole
  // (cull::appendClusters), made at load.
  const std::vector<cull::Cluster>& clusters() const { return clusters_; }
  cull::ClusterRange clusterRange() const { return clusterRange_; }

 private:
  GpuMesh(const ShapeData& data, const RunSplit& split);

  gl::Buffer vertices_;
  gl::Buffer indices_;     // 32-bit, into the copies: GPU culling's commands
  gl::Buffer runIndices_;  // 16-bit, each run's from 0: what the vertex array binds
  gl::VertexArray vao_;
  GLsizei indexCount_ = 0;
  std::vector<VertexRun> runs_;
  std::vector<cull::Cluster> clusters_;
  cull::ClusterRange clusterRange_;
};

}  // namespace engine
