#include "scene/environment.h"

#include <cmath>
#include <utility>

#include "asset/model_lights.h"

namespace engine {

SceneEnvironment SceneEnvironment::of(const SceneDesc& desc, std::shared_ptr<const FloatImage> skyImage) {
  SceneEnvironment environment;
  environment.lights = desc.lights;
  environment.sky = desc.sky;
  environment.skyImage = std::move(skyImage);
  return environment;
}

void SceneEnvironment::addModelLights(const ModelData& model, const glm::dmat4& world) {
  for (LightDesc& light : modelLights(model, world)) lights.push_back(std::move(light));
}

const LightDesc* firstSun(std::span<const LightDesc> lights) {
  for (const LightDesc& l : lights)
    if (l.type == LightType::Sun) return &l;
  return nullptr;
}

std::optional<glm::vec3> sunDirectionOf(std::span<const LightDesc> lights) {
  const LightDesc* s = firstSun(lights);
  if (!s) return std::nullopt;
  return glm::normalize(glm::vec3(s->direction));
}

LightCone lightCone(const LightDesc& light) {
  if (light.type != LightType::Spot) return LightCone{};
  LightCone cone;
  cone.axisToLight = glm::normalize(glm::vec3(light.direction));
  cone.cosOuter = float(std::cos(glm::radians(double(light.outerConeDegrees))));
  cone.cosInner = float(std::cos(glm::radians(double(light.innerConeDegrees))));
  return cone;
}

const LightDesc* SceneEnvironment::sun() const { return firstSun(lights); }

std::optional<glm::vec3> SceneEnvironment::sunDirection() const { return sunDirectionOf(lights); }

}  // namespace engine
