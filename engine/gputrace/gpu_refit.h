#pragma once
// Skinned characters refitted on the GPU: one group of the flattened scene (a
// character's BVH, gputrace/gpu_layout.h) updated in place in the tracer's buffers
// from new vertices already on the GPU: its leaves' positions and its triangles'
// normals, then its node boxes a level at a time from the deepest up (children before
// parents, a dispatch per level), then its instance's bounds. The tree keeps its
// shape, as Bvh::refit's does, and the result is what the CPU's refit then
// flattenScene give, bit for bit. Needs a current GL 4.5 context.
#include <string>

#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "gputrace/gpu_layout.h"

namespace engine::gpurt {

class GpuRefit {
 public:
  // The plan for `group` of `layout` (flattened from `scene`) and its program.
  static Result<GpuRefit> create(const rt::RtScene& scene, const rt::GpuSceneLayout& layout, int group,
                                 const std::string& shaderDir);

  // The buffers refitted: those the tracer traces (GpuTracer::buffers()).
  struct Targets {
    GLuint nodes = 0, leaves = 0, triangles = 0, instances = 0;
  };
  // `vertices`: the group's vertexCount() vertices in the plan's order (its meshes'
  // vertices one mesh after another), `stride` vec4 apart, position first and the
  // normal next (the skin cache's records are 3 apart). Issues the dispatches; a
  // barrier for shader storage reads follows them.
  void run(const gl::Buffer& vertices, int stride, const Targets& targets) const;
  std::uint32_t vertexCount() const { return plan_.vertexCount; }

 private:
  rt::GpuRefitPlan plan_;
  gl::Buffer table_;  // leaf corners, triangle corners, then each level's nodes
  gl::Program program_;
};

}  // namespace engine::gpurt
