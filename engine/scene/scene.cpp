#include "scene/scene.h"

#include <algorithm>
#include <map>
#include <optional>

#include "scene/instances.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain.h"

namespace engine {

Scene::~Scene() = default;

Result<std::shared_ptr<Scene>> Scene::load(const SceneDesc& desc) { return load(desc, {}); }

Result<std::shared_ptr<Scene>> Scene::load(const SceneDesc& desc,
                                           std::vector<std::shared_ptr<const ModelAsset>> preloaded) {
  std::shared_ptr<Scene> scene(new Scene());
  scene->desc_ = desc;
  if (desc.terrain.enabled) {
    auto created = terrain::Terrain::create(terrain::settingsFromScene(desc.terrain));
    if (!created) return makeError(desc.path + ": /terrain: " + created.error().message);
    scene->terrain_ = std::make_unique<terrain::Terrain>(std::move(created).value());
  }
  if (auto s = scene->loadModels(preloaded); !s) return s.error();
  auto images = SceneImages::load(desc);
  if (!images) return images.error();
  scene->images_ = std::move(images).value();
  scene->materials_ = sceneFileMaterials(desc, scene->images_);
  scene->environment_ = SceneEnvironment::of(desc, scene->images_.sky);
  for (const ModelInstance& instance : scene->instances_)
    scene->environment_.addModelLights(scene->assetOf(instance).model, instance.world);
  if (auto s = scene->update(0.0); !s) return s.error();
  return scene;
}

namespace {

Result<std::shared_ptr<const ModelAsset>> findOrLoad(const std::string& path,
                                                     std::span<const std::shared_ptr<const ModelAsset>> preloaded) {
  for (const auto& asset : preloaded)
    if (asset && asset->model.path == path) return asset;
  return ModelAsset::load(path);
}

}  // namespace

Status Scene::loadModels(std::span<const std::shared_ptr<const ModelAsset>> preloaded) {
  std::map<std::string, int> byPath;
  std::vector<std::optional<ModelAsset::Bounds>> bounds;
  for (size_t i = 0; i < desc_.models.size(); ++i) {
    const ModelDesc& m = desc_.models[i];
    const std::string where = desc_.path + ": /models/" + std::to_string(i);
    auto [it, fresh] = byPath.emplace(m.path, int(assets_.size()));
    if (fresh) {
      auto asset = findOrLoad(m.path, preloaded);
      if (!asset) return makeError(where + "/path: " + asset.error().message);
      auto b = (*asset)->boundsOfAllPoses();
      if (!b) return makeError(where + ": " + b.error().message);
      assets_.push_back(std::move(asset).value());
      bounds.emplace_back(*b);
    }
    ModelInstance instance;
    instance.asset = it->second;
    instance.desc = m;
    const ModelAsset& asset = *assets_[size_t(instance.asset)];
    auto clip = findClip(asset.animated, m.clip, m.path);
    if (!clip) return makeError(where + "/clip: " + clip.error().message);
    instance.clip = *clip;
    const double ground = m.onTerrain && terrain_ ? terrain_->heightAt(m.position.x, m.position.z) : 0.0;
    instance.world = modelTransform(m, ground);
    const ModelAsset::Bounds& b = *bounds[size_t(instance.asset)];
    instance.boundsCenter = glm::dvec3(b.min + b.max) * 0.5;
    instance.boundsRadius = 0.5 * double(glm::length(b.max - b.min)) * std::max({m.scale.x, m.scale.y, m.scale.z});
    instances_.push_back(std::move(instance));
  }
  return Ok{};
}

Status Scene::update(double time, QuatInterpolation rotations) {
  if (posed_ && time == time_ && rotations == rotations_) return Ok{};
  for (size_t i = 0; i < instances_.size(); ++i) {
    ModelInstance& instance = instances_[i];
    if (auto s = samplePose(assetOf(instance), instance.clip, clipTimeAt(instance.desc, time), locals_, instance.pose,
                            rotations);
        !s) {
      return makeError(desc_.path + ": /models/" + std::to_string(i) + ": " + s.error().message);
    }
  }
  time_ = time;
  rotations_ = rotations;
  posed_ = true;
  return Ok{};
}

}  // namespace engine
