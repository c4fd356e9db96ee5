#include "asset/material_texture.h"

#include "core/procedural_image.h"

namespace engine {

Result<Image> loadMaterialTexture(const SceneDesc& scene, const MaterialDesc& material) {
  if (material.texture.empty()) return Image{};
  if (material.texture == "checker") return makeChecker(256, 2, {235, 235, 235}, {90, 90, 90});
  const auto folder = scene.path.substr(0, scene.path.find_last_of('/') + 1);
  auto image = readPng(folder + material.texture);
  if (!image) return makeError(scene.path + ": /materials/" + material.name + "/texture: " + image.error().message);
  return image;
}

}  // namespace engine
