#pragma once
// The lights every renderer draws, in the engine's units (asset/scene_desc.h): the
// scene file's own, then each model instance's KHR_lights_punctual lights
// (asset/model_lights.h: lux and candela taken as sun and point units), placed by
// the instance's root in the rest pose. Neither renderer reads a glTF light itself.
#include <memory>
#include <span>
#include <vector>

#include "asset/scene_desc.h"

namespace engine {

struct ModelAsset;
struct ModelInstance;

std::vector<LightDesc> sceneLights(const SceneDesc& desc, std::span<const std::shared_ptr<const ModelAsset>> assets,
                                   std::span<const ModelInstance> instances);

}  // namespace engine
