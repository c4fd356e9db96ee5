#pragma once
// The scene file's own images, decoded once when the scene loads: each material's
// texture ("checker" made, a PNG read) and the sky's image. Every renderer takes
// them from here (the rasterizer uploads them, the tracers sample them), so a
// renderer rebuilt by the trade panel or a reference traced beside it reads no
// file. glTF images are decoded with their model (scene/model_asset.h).
#include <memory>
#include <vector>

#include "asset/scene_desc.h"
#include "core/image.h"
#include "core/linear_image.h"
#include "core/result.h"

namespace engine {

struct SceneImages {
  // One per scene material, in the file's order; null where it has no texture.
  std::vector<std::shared_ptr<const Image>> materialTextures;
  // The sky's image in linear floats; null without an image sky.
  std::shared_ptr<const FloatImage> sky;

  // Errors name the scene file and the key: "room.json: /materials/floor/texture:
  // tiles.png: cannot open", "demo.json: /sky/image: ...".
  static Result<SceneImages> load(const SceneDesc& desc);
  const Image* materialTexture(std::size_t material) const {
    return material < materialTextures.size() ? materialTextures[material].get() : nullptr;
  }
};

}  // namespace engine
