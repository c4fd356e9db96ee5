#include "scene/scene_images.h"

#include "asset/material_texture.h"

namespace engine {

Result<SceneImages> SceneImages::load(const SceneDesc& desc) {
  SceneImages images;
  // The sky first: the rasterizer used to report a bad sky before a bad texture.
  if (desc.sky.enabled && !desc.sky.image.empty()) {
    auto sky = readLinearImage(desc.sky.image);
    if (!sky) return makeError(desc.path + ": /sky/image: " + sky.error().message);
    images.sky = std::make_shared<const FloatImage>(std::move(sky).value());
  }
  for (const MaterialDesc& m : desc.materials) {
    auto image = loadMaterialTexture(desc, m);
    if (!image) return image.error();
    images.materialTextures.push_back(image->empty() ? nullptr : std::make_shared<const Image>(std::move(image).value()));
  }
  return images;
}

}  // namespace engine
