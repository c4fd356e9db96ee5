#include "scene/scene_lights.h"

#include "asset/model_lights.h"
#include "scene/scene.h"

namespace engine {

std::vector<LightDesc> sceneLights(const SceneDesc& desc, std::span<const std::shared_ptr<const ModelAsset>> assets,
                                   std::span<const ModelInstance> instances) {
  std::vector<LightDesc> lights = desc.lights;
  for (const ModelInstance& instance : instances) {
    const std::vector<LightDesc> own = modelLights(assets[std::size_t(instance.asset)]->model, instance.world);
    lights.insert(lights.end(), own.begin(), own.end());
  }
  return lights;
}

}  // namespace engine
