#include "gputrace/gpu_refit.h"

#include "gl/bindings.h"

namespace engine::gpurt {
namespace {

enum Stage { kLeaves = 0, kTriangles = 1, kNodes = 2, kInstance = 3 };

// The plan's tables in one array of uvec4, as refit.comp reads them.
std::vector<glm::uvec4> tableOf(const rt::GpuRefitPlan& plan) {
  std::vector<glm::uvec4> table = plan.leafCorners;
  table.insert(table.end(), plan.triangleCorners.begin(), plan.triangleCorners.end());
  for (const auto& level : plan.levels) {
    for (const std::uint32_t node : level) table.emplace_back(node, 0u, 0u, 0u);
  }
  if (table.empty()) table.emplace_back(0u);  // GL wants a size
  return table;
}

}  // namespace

Result<GpuRefit> GpuRefit::create(const rt::RtScene& scene, const rt::GpuSceneLayout& layout, int group,
                                  const std::string& shaderDir) {
  if (group < 0 || group >= scene.groupCount()) return makeError("GpuRefit: no group " + std::to_string(group));
  GpuRefit refit;
  refit.plan_ = rt::refitPlan(scene, layout, group);
  refit.table_ = gl::Buffer::fromSpan(std::span<const glm::uvec4>(tableOf(refit.plan_)));
  auto program = gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, "rt/refit.comp"}},
                                    {"RT_WIDTH " + std::to_string(layout.width)});
  if (!program) return program.error();
  refit.program_ = std::move(program).value();
  return refit;
}

void GpuRefit::run(const gl::Buffer& vertices, int stride, const Targets& targets) const {
  const std::pair<unsigned, GLuint> buffers[] = {
      {gl::binding::kRtNodes, targets.nodes},         {gl::binding::kRtLeaves, targets.leaves},
      {gl::binding::kRtTriangles, targets.triangles}, {gl::binding::kRtInstances, targets.instances},
      {gl::binding::kRtInput, vertices.id()},         {gl::binding::kRtRefitPlan, table_.id()}};
  for (const auto& [unit, buffer] : buffers) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, unit, buffer);
  program_.use();
  glUniform1ui(program_.location("u_stride"), GLuint(stride));
  GLuint first = 0;
  const auto dispatch = [&](Stage stage, std::size_t count, std::uint32_t base) {
    program_.set("u_stage", int(stage));
    glUniform1ui(program_.location("u_first"), first);
    glUniform1ui(program_.location("u_count"), GLuint(count));
    glUniform1ui(program_.location("u_base"), base);
    if (count > 0) glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    // Each step reads what the one before wrote.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  first = GLuint(plan_.leafCorners.size());  // the triangles' table follows the leaves'
  dispatch(kTriangles, plan_.triangleCorners.size(), plan_.firstTriangle);
  if (plan_.instance < 0) return;
  first = 0;
  dispatch(kLeaves, plan_.leafCorners.size() / 4, plan_.firstLeaf);
  first = GLuint(plan_.leafCorners.size() + plan_.triangleCorners.size());
  for (const auto& level : plan_.levels) {
    dispatch(kNodes, level.size(), 0);
    first += GLuint(level.size());
  }
  dispatch(kInstance, 1, std::uint32_t(plan_.instance));
}

}  // namespace engine::gpurt
