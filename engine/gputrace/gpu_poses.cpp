#include "gputrace/gpu_poses.h"

namespace engine::gpurt {
namespace {

// The refit's vertex array holds the vertices of the group's meshes that have
// triangles, mesh after mesh (rt::refitPlan).
bool hasTriangles(const rt::RtMesh& mesh) { return mesh.indices.size() >= 3; }

}  // namespace

Result<GpuPoses> GpuPoses::create(const rt::AnimatedRtScene& scene, const GpuTracer& tracer, const std::string& shaderDir) {
  GpuPoses poses;
  for (std::size_t i = 0; i < scene.instanceCount(); ++i) {
    auto refit = GpuRefit::create(scene.scene(), tracer.layout(), scene.instanceGroup(i), shaderDir);
    if (!refit) return refit.error();
    Instance instance{std::move(refit).value(), {}, {}};
    std::size_t count = 0;
    for (const rt::RtMesh& mesh : scene.instanceMeshes(i)) count += hasTriangles(mesh) ? mesh.positions.size() : 0;
    if (count != instance.refit.vertexCount()) {
      return makeError("model instance " + std::to_string(i) + ": " + std::to_string(count) +
                       " vertices posed, the refit expects " + std::to_string(instance.refit.vertexCount()));
    }
    instance.staging.resize(2 * std::size_t(instance.refit.vertexCount()));
    instance.vertices = gl::Buffer::create(std::max<std::size_t>(16, instance.staging.size() * sizeof(glm::vec4)));
    poses.instances_.push_back(std::move(instance));
  }
  return poses;
}

void GpuPoses::update(const rt::AnimatedRtScene& scene, const GpuTracer& tracer) {
  vertices_ = 0;
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    Instance& instance = instances_[i];
    std::size_t next = 0;
    for (const rt::RtMesh& mesh : scene.instanceMeshes(i)) {
      if (!hasTriangles(mesh)) continue;
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        instance.staging[next++] = glm::vec4(mesh.positions[v], 1.0f);
        instance.staging[next++] = glm::vec4(mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[v], 0.0f);
      }
    }
    if (next == 0) continue;
    instance.vertices.upload(0, next * sizeof(glm::vec4), instance.staging.data());
    instance.refit.run(instance.vertices, 2, tracer.buffers());
    vertices_ += next / 2;
  }
}

}  // namespace engine::gpurt
