#pragma once
// The material test model (assets/models/materials.gltf): one static mesh per
// glTF material feature, with textures painted here, so the renderer's material
// model can be seen and tested without borrowing anyone's model:
//   a brick wall       base colour, normal map and TANGENT attribute, an ORM map
//                      (occlusion R, roughness G, metallic B: occlusion + MR textures)
//   a tiled sphere     normal map (exact TANGENTs along u) and a metallic-roughness
//                      checker of metal and rough tiles
// (Tangent generation for files without TANGENT is tested on its own: the Khronos
// validator warns about such files, and shipped models are validator-clean.)
//   an emissive panel  emissive texture (sRGB)
//   a leafy bush       alpha MASK, double-sided crossed cards
//   two glass panes    alpha BLEND, tinted, one behind the other
//   two quads          seen from behind: double-sided (drawn) and single-sided (culled)
// Deterministic to the bit, like the robot.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace assetgen {

struct MaterialsModel {
  std::string json;
  std::vector<std::uint8_t> bin;
  std::vector<std::pair<std::string, engine::Image>> images;  // file name, pixels
};

// `baseName` names the .bin and every image (`<baseName>_bricks_normal.png`, ...).
MaterialsModel buildMaterialsModel(const std::string& baseName);

}  // namespace assetgen
