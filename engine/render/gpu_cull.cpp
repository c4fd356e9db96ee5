#include "render/gpu_cull.h"

#include <algorithm>

#include "gl/bindings.h"

namespace engine {
namespace {

constexpr GLuint kHiZGroup = 8;  // hiz.comp's local size, each way

// A buffer of at least `bytes` (at least one byte: a buffer may not be empty),
// grown by doubling so that a scene's frames settle on one.
void reserve(gl::Buffer& buffer, std::size_t bytes) {
  bytes = std::max<std::size_t>(bytes, 1);
  if (buffer && buffer.size() >= bytes) return;
  buffer = gl::Buffer::create(std::max(bytes, 2 * (buffer ? buffer.size() : 0)), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

}  // namespace

Result<HiZPyramid> HiZPyramid::create(const std::string& shaderDir, GLenum depthFormat) {
  auto program = gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, "cull/hiz.comp"}});
  if (!program) return program.error();
  HiZPyramid hiz;
  hiz.program_ = std::move(program).value();
  hiz.depthFormat_ = depthFormat;
  hiz.depthFbo_ = gl::Framebuffer::create();
  // Depth only: an occluder prepass draws into it with no colour.
  glNamedFramebufferDrawBuffer(hiz.depthFbo_.id(), GL_NONE);
  glNamedFramebufferReadBuffer(hiz.depthFbo_.id(), GL_NONE);
  return hiz;
}

void HiZPyramid::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  levels_ = cull::hizLevelCount(width, height);
  depth_ = gl::Texture::create2D(depthFormat_, width, height, 1);
  depth_.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  depth_.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  depthFbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
  // Levels 1 to levels_ as the texture's mips 0 to levels_ - 1.
  pyramid_ = gl::Texture::create2D(GL_R32F, std::max(1, width >> 1), std::max(1, height >> 1), levels_);
  pyramid_.parameter(GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  pyramid_.parameter(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

void HiZPyramid::copyDepth(GLuint framebuffer, int width, int height) {
  resize(width, height);
  glBlitNamedFramebuffer(framebuffer, depthFbo_.id(), 0, 0, width, height, 0, 0, width, height,
                         GL_DEPTH_BUFFER_BIT, GL_NEAREST);
}

void HiZPyramid::reduce() {
  const int width = width_, height = height_;
  program_.use();
  for (int level = 1; level <= levels_; ++level) {
    const glm::ivec2 size(std::max(1, width >> level), std::max(1, height >> level));
    const glm::ivec2 source(std::max(1, width >> (level - 1)), std::max(1, height >> (level - 1)));
    // Level 1 reads the copied depth; every other level the one below it, which
    // the barrier after the previous dispatch made visible to texel fetches.
    glBindTextureUnit(gl::binding::kHiZSource, level == 1 ? depth_.id() : pyramid_.id());
    glBindImageTexture(gl::binding::kHiZLevelImage, pyramid_.id(), level - 1, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    program_.set("u_sourceLevel", std::max(level - 2, 0));
    glProgramUniform2i(program_.id(), program_.location("u_sourceSize"), source.x, source.y);
    glProgramUniform2i(program_.id(), program_.location("u_size"), size.x, size.y);
    glDispatchCompute((GLuint(size.x) + kHiZGroup - 1) / kHiZGroup, (GLuint(size.y) + kHiZGroup - 1) / kHiZGroup, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  glBindTextureUnit(gl::binding::kHiZSource, 0);
}

cull::HiZ HiZPyramid::read() const {
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  cull::HiZ hiz;
  hiz.width = width_;
  hiz.height = height_;
  for (int level = 1; level <= levels_; ++level) {
    std::vector<float> texels(size_t(hiz.levelWidth(level)) * size_t(hiz.levelHeight(level)));
    glGetTextureImage(pyramid_.id(), level - 1, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                      texels.data());
    hiz.levels.push_back(std::move(texels));
  }
  return hiz;
}

Result<GpuCuller> GpuCuller::create(const std::string& shaderDir) {
  auto program = gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, "cull/cull.comp"}});
  if (!program) return program.error();
  GpuCuller culler;
  culler.program_ = std::move(program).value();
  const cull::Counters zero;  // read back before any frame: zeros, not whatever the GL left
  culler.counterBuffer_ = gl::Buffer::create(sizeof(cull::Counters), &zero, GL_DYNAMIC_STORAGE_BIT);
  return culler;
}

std::uint32_t GpuCuller::addClusters(std::span<const cull::Cluster> clusters) {
  const auto first = std::uint32_t(clusters_.size());
  clusters_.insert(clusters_.end(), clusters.begin(), clusters.end());
  clustersUploaded_ = false;
  return first;
}

void GpuCuller::clearClusters() {
  clusters_.clear();
  clustersUploaded_ = false;
}

void GpuCuller::clearJobs() {
  jobs_.clear();
  commandTotal_ = 0;
}

std::size_t GpuCuller::addJob(cull::Job job) {
  job.firstCommand = commandTotal_;
  commandTotal_ += cull::commandCount(job);
  jobs_.push_back(job);
  return jobs_.size() - 1;
}

IndirectDraw GpuCuller::commandsOf(std::size_t job) const {
  const cull::Job& j = jobs_[job];
  return {GLintptr(j.firstCommand) * GLintptr(sizeof(cull::Command)), GLsizei(cull::commandCount(j))};
}

void GpuCuller::upload() {
  if (!clustersUploaded_) {
    reserve(clusterBuffer_, clusters_.size() * sizeof(cull::Cluster));
    if (!clusters_.empty()) clusterBuffer_.upload(0, clusters_.size() * sizeof(cull::Cluster), clusters_.data());
    clustersUploaded_ = true;
  }
  reserve(jobBuffer_, jobs_.size() * sizeof(cull::Job));
  if (!jobs_.empty()) jobBuffer_.upload(0, jobs_.size() * sizeof(cull::Job), jobs_.data());
  reserve(commandBuffer_, std::size_t(commandTotal_) * sizeof(cull::Command));
  const cull::Counters zero;
  counterBuffer_.upload(0, sizeof zero, &zero);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commandBuffer_.id());
}

void GpuCuller::bindCommands() const { glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commandBuffer_.id()); }

void GpuCuller::cull(std::size_t first, std::size_t end, const glm::mat4& viewProjection, const HiZPyramid* hiz,
                     float depthMargin) {
  if (end <= first) return;
  program_.use();
  program_.set("u_depthMargin", depthMargin);
  program_.set("u_viewProjection", viewProjection);
  program_.set("u_levels", hiz ? hiz->levels() : 0);
  glProgramUniform2i(program_.id(), program_.location("u_size"), hiz ? hiz->width() : 1, hiz ? hiz->height() : 1);
  glProgramUniform1ui(program_.id(), program_.location("u_firstJob"), GLuint(first));
  // Without a pyramid cull.comp never samples u_hiz (u_levels 0).
  if (hiz) glBindTextureUnit(gl::binding::kHiZ, hiz->texture().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kCullClusters, clusterBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kCullJobs, jobBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kCullCommands, commandBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kCullCounters, counterBuffer_.id());
  glDispatchCompute(GLuint(end - first), 1, 1);
  // The draws read the commands as indirect arguments.
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

cull::Counters GpuCuller::counters() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  cull::Counters c;
  glGetNamedBufferSubData(counterBuffer_.id(), 0, sizeof c, &c);
  return c;
}

std::vector<cull::Command> GpuCuller::commands() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<cull::Command> out(commandTotal_);
  if (!out.empty()) glGetNamedBufferSubData(commandBuffer_.id(), 0, GLsizeiptr(out.size() * sizeof(cull::Command)), out.data());
  return out;
}

}  // namespace engine
