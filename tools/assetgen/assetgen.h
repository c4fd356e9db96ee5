#pragma once
// The generator as a library: build the robot and write it as glTF files. main.cpp
// only parses the command line; the tests call these directly.
#include <string>

#include "character.h"
#include "core/result.h"

namespace assetgen {

// The names the files get inside the output folder.
struct OutputNames {
  std::string gltf;
  std::string bin;
  std::string image;
};

OutputNames outputNames(const std::string& baseName);

// The project's robot: skeleton, skinned mesh, albedo atlas and clips. The same
// every time, to the bit.
Character buildRobot();

// Writes `<baseName>.gltf`, `.bin` and `_albedo.png` into `folder` (created when
// missing). Each file is written beside its final name and renamed into place, and
// the .gltf comes last, so a failure never leaves a model that refers to missing
// files. Errors name the path.
engine::Status writeCharacter(const Character& character, const std::string& folder,
                              const std::string& baseName);

// Writes the material test model (materials_model.h) as `<baseName>.gltf`, `.bin`
// and `<baseName>_*.png` into `folder`, in the same order and as safely.
engine::Status writeMaterialsModel(const std::string& folder, const std::string& baseName);

}  // namespace assetgen
