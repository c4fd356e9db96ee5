#pragma once
// The ray tracer's view of a scene at one time: the analytic primitives and lights
// of the SceneDesc, plus every glTF model instance as the scene layer posed it
// (scene/scene.h), skinned on the CPU with the same jobs and palettes the
// rasterizer uses (anim/jobs.h), as triangle meshes in the BVH.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/scene_desc.h"
#include "core/image.h"
#include "core/result.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"

namespace engine {
class Scene;
}

namespace engine::rt {

// One model instance (a character): its triangles, the time its pose took (sample,
// local-to-model, skin) and its BVH's build (create) or refit (setTime).
struct InstanceStats {
  int triangles = 0;
  double skinSeconds = 0.0;
  double bvhSeconds = 0.0;
};

struct SceneBuildStats {
  int meshes = 0;
  int triangles = 0;
  double skinSeconds = 0.0;
  double bvhSeconds = 0.0;
  std::vector<InstanceStats> instances;  // in the scene file's order
};

// A scene file's ray-traced view that follows time: the static world (primitives,
// terrain) in BVH group 0, built once; each model instance in a group of its own,
// skinned on the CPU at the new time and refitted (not rebuilt) by setTime.
class AnimatedRtScene {
 public:
  // Errors name the scene file and the model element, like the rasterizer's. The
  // terrain is triangulated exactly as the rasterizer draws it for this camera and
  // an image `viewportHeight` pixels high (the same CDLOD selection and morph).
  // The scene layer's scene (scene/scene.h) at its current time; the tracer keeps
  // it and skins its poses.
  // `camera`, when given, replaces the file's: the view traced and the one the
  // terrain is triangulated for (the trade panel's reference of the window's view).
  // `terrainErrorOverride` > 0 replaces the file's LOD target, as the rasterizer's
  // option of that name does (the trade panel's knob, demo --terrain-error).
  static Result<AnimatedRtScene> create(std::shared_ptr<Scene> scene, int viewportHeight = 720,
                                        SceneBuildStats* stats = nullptr, const CameraDesc* camera = nullptr,
                                        double terrainErrorOverride = 0.0);
  // Scene::load and update(time), then the above.
  static Result<AnimatedRtScene> create(const SceneDesc& scene, double time, int viewportHeight = 720,
                                        SceneBuildStats* stats = nullptr);
  // Poses the scene at `time` (Scene::update), skins every model instance and
  // refits its BVH; stats cover only them.
  Status setTime(double time, SceneBuildStats* stats = nullptr);

  RtScene& scene() { return scene_; }
  const RtScene& scene() const { return scene_; }
  // The scene's model instances: each one's BVH group of the RtScene and its meshes as
  // last posed (world space, in the group's order: what a GPU refit reads).
  std::size_t instanceCount() const { return instances_.size(); }
  int instanceGroup(std::size_t i) const { return instances_[i].group; }
  const std::vector<RtMesh>& instanceMeshes(std::size_t i) const { return instances_[i].meshes; }
  // The RtScene material of each glTF material of the scene's asset `asset`
  // (Scene::assets() order), made from its table (ModelAsset::materials), and last
  // glTF's default (gltfDefaultMaterial), which its primitives without one take.
  std::span<const int> assetMaterials(std::size_t asset) const { return materials_[asset]; }

  AnimatedRtScene(AnimatedRtScene&&) noexcept;
  AnimatedRtScene& operator=(AnimatedRtScene&&) noexcept;
  ~AnimatedRtScene();

 private:
  AnimatedRtScene();

  // Scene instance `index` in its current pose into `meshes`.
  Status skin(size_t index, std::vector<RtMesh>& meshes) const;

  // The ray-traced side of a scene instance, in the scene's order.
  struct Instance {
    int group = 0;
    std::vector<RtMesh> meshes;  // the pose being built; copied into the scene
    std::vector<MeshId> ids;
  };
  RtScene scene_;
  std::shared_ptr<Scene> source_;
  std::vector<std::vector<int>> materials_;  // per scene asset: glTF material -> RtScene material
  std::vector<Instance> instances_;
};

// A scene file's analytic part (shapes, lights, materials, camera, sky; no models or
// terrain), its images decoded by the scene layer: for tests, tools and benchmarks.
Result<RtScene> analyticRtScene(const SceneDesc& scene);

// The scene at one time, as AnimatedRtScene::create builds it.
Result<RtScene> buildRtScene(const SceneDesc& scene, double time, int viewportHeight = 720,
                             SceneBuildStats* stats = nullptr);

struct RaytraceRun {
  Image image;  // tone mapped and encoded as the scene's render settings say
  RenderResult result;
  SceneBuildStats build;
};

// The whole ray-traced frame: scene at `time`, rendered, converted to 8 bits.
Result<RaytraceRun> raytraceScene(const SceneDesc& scene, double time, const RenderSettings& settings);

}  // namespace engine::rt
