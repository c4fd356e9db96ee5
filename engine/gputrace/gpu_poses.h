#pragma once
// A moving scene traced on the GPU: after AnimatedRtScene::setTime has posed its
// characters (the scene layer's poses, skinned and morphed), each character's new
// vertices are uploaded and its BVH group refitted in the GPU tracer's own buffers
// (GpuRefit), so a new pose costs its vertices' upload and a refit, not a new
// flattening and upload of the scene. The refitted tree is the CPU's refit flattened,
// bit for bit, so the image is the one a tracer made from the posed scene gives.
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "gputrace/gpu_refit.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/scene_builder.h"

namespace engine::gpurt {

class GpuPoses {
 public:
  // A refit for each model instance of `scene`, whose RtScene `tracer` traces.
  static Result<GpuPoses> create(const rt::AnimatedRtScene& scene, const GpuTracer& tracer, const std::string& shaderDir);

  // Uploads every instance's vertices as `scene` last posed them and refits its group.
  void update(const rt::AnimatedRtScene& scene, const GpuTracer& tracer);
  // Vertices uploaded by the last update.
  std::size_t vertices() const { return vertices_; }

 private:
  struct Instance {
    GpuRefit refit;
    gl::Buffer vertices;  // position, normal: two vec4 a vertex
    std::vector<glm::vec4> staging;
  };
  std::vector<Instance> instances_;
  std::size_t vertices_ = 0;
};

}  // namespace engine::gpurt
