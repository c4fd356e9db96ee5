#pragma once
// The scene at time t, as both renderers consume it, GL-free: every glTF the scene
// file names loaded once, every model instance placed in double precision and posed
// once per update, the terrain's height field, and the scene file's images. Neither the rasterizer
// (render/scene_renderer.h) nor the tracers (raytrace/scene_builder.h) load a model,
// sample a clip or build the field themselves, so what they draw cannot drift.
#include <memory>
#include <span>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "scene/environment.h"
#include "scene/materials.h"
#include "scene/model_asset.h"
#include "scene/scene_images.h"

namespace engine {

namespace terrain {
class Terrain;
}

// One entry of the scene file's models, posed at the scene's time.
struct ModelInstance {
  int asset = -1;  // into Scene::assets()
  ModelDesc desc;
  int clip = -1;            // -1: the rest pose
  glm::dmat4 world{1.0};    // the instance's root: the file's transform, on the terrain when it says so
  glm::dvec3 boundsCenter{0.0};  // model space, of every pose of every clip
  double boundsRadius = 1.0;     // world units: the bounds' half diagonal times the largest scale
  Pose pose;                     // at the last update; joints in model space
};

class Scene {
 public:
  // Loads every model (each file once) and the terrain. Errors name the scene
  // file and the element: "demo.json: /models/2/clip: no clip ...".
  static Result<std::shared_ptr<Scene>> load(const SceneDesc& desc);
  // The same, with models already in memory: an entry of desc.models whose path is
  // a preloaded asset's model.path uses that asset instead of reading the file
  // (the viewer, which loaded the model to frame and dump it).
  static Result<std::shared_ptr<Scene>> load(const SceneDesc& desc,
                                             std::vector<std::shared_ptr<const ModelAsset>> preloaded);
  ~Scene();

  // Poses every instance at scene time `time` (seconds): clip time is
  // start + time * speed, so a pose never depends on the updates before it. A
  // second update at the same time (and interpolation) does nothing. `rotations`
  // is the rasterizer's knob: the tracers, the truth, always pose with slerp.
  Status update(double time, QuatInterpolation rotations = QuatInterpolation::Slerp);
  double time() const { return time_; }
  // Replaces instance `instance`'s pose with one made elsewhere (the viewer's
  // player: cross-fades, scrubbing, loop modes), until the next update at a new time.
  void setPose(int instance, const Pose& pose) { instances_[size_t(instance)].pose = pose; }

  const SceneDesc& desc() const { return desc_; }
  std::span<const std::shared_ptr<const ModelAsset>> assets() const { return assets_; }
  const ModelAsset& assetOf(const ModelInstance& instance) const { return *assets_[size_t(instance.asset)]; }
  std::span<const ModelInstance> instances() const { return instances_; }
  // The height field, or null without terrain. Not const: it pages heights in.
  terrain::Terrain* terrain() const { return terrain_.get(); }
  // The scene file's material textures and sky image, decoded once at load.
  const SceneImages& images() const { return images_; }
  // The scene file's materials as both renderers shade them (scene/materials.h),
  // their textures in images(); a model's are its asset's (ModelAsset::materials).
  std::span<const SceneMaterial> materials() const { return materials_; }
  // The lights (the file's, then each instance's KHR_lights_punctual) and the sky, as
  // every renderer draws them (scene/environment.h).
  const SceneEnvironment& environment() const { return environment_; }
  // Whether anything in the scene moves with time (today: whether it has models).
  bool animated() const { return !instances_.empty(); }

 private:
  Scene() = default;
  Status loadModels(std::span<const std::shared_ptr<const ModelAsset>> preloaded);

  SceneDesc desc_;
  std::vector<std::shared_ptr<const ModelAsset>> assets_;
  std::vector<ModelInstance> instances_;
  std::unique_ptr<terrain::Terrain> terrain_;
  SceneImages images_;
  std::vector<SceneMaterial> materials_;
  SceneEnvironment environment_;
  std::vector<Srt> locals_;  // scratch of update
  double time_ = 0.0;
  QuatInterpolation rotations_ = QuatInterpolation::Slerp;
  bool posed_ = false;
};

}  // namespace engine
