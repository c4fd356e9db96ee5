#include "asset/model_lights.h"

#include <utility>

#include "core/math.h"

namespace engine {
namespace {

glm::dmat4 localMatrix(const NodeData& node) {
  Srt srt;
  srt.translation = node.translation;
  srt.rotation = node.rotation;
  srt.scale = node.scale;
  return glm::dmat4(toMatrix(srt));
}

LightDesc sceneLight(const PunctualLightData& light, const glm::dmat4& world) {
  LightDesc out;
  out.color = light.color;
  out.intensity = light.intensity;
  out.shadows = false;
  // glTF's lights shine along the node's -Z: toward the light is its +Z. A node
  // scaled to nothing has no direction: straight down, as a noon sun.
  const glm::dvec3 toLight(world * glm::dvec4(0.0, 0.0, 1.0, 0.0));
  out.direction = glm::length(toLight) > 1e-12 ? glm::normalize(toLight) : glm::dvec3(0.0, 1.0, 0.0);
  if (light.type == PunctualType::Directional) {
    out.type = LightType::Sun;
    return out;
  }
  out.type = light.type == PunctualType::Spot ? LightType::Spot : LightType::Point;
  out.position = glm::dvec3(world[3]);
  out.falloff = true;
  out.innerConeDegrees = float(glm::degrees(double(light.innerConeAngle)));
  out.outerConeDegrees = float(glm::degrees(double(light.outerConeAngle)));
  return out;
}

}  // namespace

// Depth first with a stack of its own, not recursion: a chain of 2^20 nodes (the
// loader's limit) would overflow the call stack. The tree was checked on load.
std::vector<LightDesc> modelLights(const ModelData& model, const glm::dmat4& root) {
  std::vector<LightDesc> out;
  if (model.lights.empty()) return out;
  std::vector<std::pair<int, glm::dmat4>> stack;
  for (auto r = model.sceneRoots.rbegin(); r != model.sceneRoots.rend(); ++r) stack.emplace_back(*r, root);
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    const NodeData& n = model.nodes[std::size_t(node)];
    const glm::dmat4 world = parent * localMatrix(n);
    if (n.light >= 0) out.push_back(sceneLight(model.lights[std::size_t(n.light)], world));
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.emplace_back(*c, world);
  }
  return out;
}

}  // namespace engine
