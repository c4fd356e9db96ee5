#pragma once
// GPU culling (issue 16, render.gpu_culling): the main view's instances and their
// clusters (render/cull_math.h) culled in a compute shader against the frustum and
// a hierarchical-Z pyramid of the depth drawn so far, writing the
// glMultiDrawElementsIndirect commands the draws then submit. The CPU never reads
// the verdicts back: a culled mesh is still submitted, with empty commands.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/cull_math.h"
#include "render/model_renderer.h"

namespace engine {

// The pyramid of one framebuffer's depth (cull/hiz.comp; cull::HiZ is its twin).
class HiZPyramid {
 public:
  // `depthFormat`: the format of the depth it copies (a blit copies between equal
  // formats only), GL_DEPTH_COMPONENT32F or GL_DEPTH32F_STENCIL8.
  static Result<HiZPyramid> create(const std::string& shaderDir, GLenum depthFormat = GL_DEPTH_COMPONENT32F);
  // From the depth of `framebuffer` (32-bit float, single-sample) of width x
  // height pixels: copied by a blit (the depth may be a renderbuffer), then reduced.
  void build(GLuint framebuffer, int width, int height) {
    copyDepth(framebuffer, width, height);
    reduce();
  }
  // The two steps apart, so that more may be drawn into the copy between them (an
  // occluder prepass): the copy's framebuffer, depth only, is depthFramebuffer().
  void copyDepth(GLuint framebuffer, int width, int height);
  GLuint depthFramebuffer() const { return depthFbo_.id(); }
  void reduce();
  const gl::Texture& texture() const { return pyramid_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int levels() const { return levels_; }
  // Every level read back (waits for the GL): for tests.
  cull::HiZ read() const;

 private:
  void resize(int width, int height);
  gl::Program program_;
  GLenum depthFormat_ = GL_DEPTH_COMPONENT32F;
  gl::Texture depth_, pyramid_;
  gl::Framebuffer depthFbo_;
  int width_ = 0, height_ = 0, levels_ = 0;
};

class GpuCuller {
 public:
  static Result<GpuCuller> create(const std::string& shaderDir);

  // At load: appends a mesh's clusters (cull::appendClusters) to the table and
  // returns where they start (to add to their ClusterRange::first).
  std::uint32_t addClusters(std::span<const cull::Cluster> clusters);
  // Drops the table (a terrain's patches change every frame).
  void clearClusters();

  // Each frame: the jobs (an instance of a mesh each) in the order they will be
  // drawn; addJob assigns each its commands and returns its index.
  void clearJobs();
  std::size_t addJob(cull::Job job);
  std::size_t jobCount() const { return jobs_.size(); }
  // Where a job's commands lie in the command buffer, for drawMesh.
  IndirectDraw commandsOf(std::size_t job) const;
  // Uploads the jobs (and the table, once), sizes the command buffer, zeroes the
  // counters and binds the commands to GL_DRAW_INDIRECT_BUFFER.
  void upload();
  // Binds the commands cull() writes as GL_DRAW_INDIRECT_BUFFER (upload() does too).
  void bindCommands() const;
  // Culls jobs [first, end) for a view (camera-relative world -> clip, reverse-Z),
  // against `hiz`, or the frustum only (null). Commands are ready for drawing.
  // `depthMargin`: cull::View's (tests only change it).
  void cull(std::size_t first, std::size_t end, const glm::mat4& viewProjection, const HiZPyramid* hiz,
            float depthMargin = cull::kDepthMargin);

  // Reads back (waits for the GL): the counters since the last upload, every command.
  cull::Counters counters() const;
  std::vector<cull::Command> commands() const;
  const std::vector<cull::Cluster>& clusters() const { return clusters_; }
  const std::vector<cull::Job>& jobs() const { return jobs_; }

 private:
  gl::Program program_;
  std::vector<cull::Cluster> clusters_;
  std::vector<cull::Job> jobs_;
  std::uint32_t commandTotal_ = 0;
  bool clustersUploaded_ = false;
  gl::Buffer clusterBuffer_, jobBuffer_, commandBuffer_, counterBuffer_;
};

}  // namespace engine
