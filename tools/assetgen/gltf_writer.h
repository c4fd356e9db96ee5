#pragma once
// Serialises a Character as glTF 2.0: the JSON text and the bytes of its one
// external buffer. Output is deterministic: keys in a fixed order, floats printed as
// the shortest text that reads back to the same 32-bit value.
#include <cstdint>
#include <string>
#include <vector>

#include "character.h"

namespace assetgen {

struct GltfFiles {
  std::string json;
  std::vector<std::uint8_t> bin;
};

// `binUri` and `imageUri` are the names the JSON refers to, relative to the .gltf.
GltfFiles toGltf(const Character& character, const std::string& binUri,
                 const std::string& imageUri);

}  // namespace assetgen
