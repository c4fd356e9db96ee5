#pragma once
// The image a scene material's "texture" names, the same for the rasterizer and the
// ray tracer: "" none, "checker" the built-in checkerboard, anything else a PNG file
// relative to the scene file.
#include "asset/scene_desc.h"
#include "core/image.h"
#include "core/result.h"

namespace engine {

// An empty image for no texture; errors name the scene file and the material:
// "room.json: /materials/floor/texture: tiles.png: cannot open".
Result<Image> loadMaterialTexture(const SceneDesc& scene, const MaterialDesc& material);

}  // namespace engine
