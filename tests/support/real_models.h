#pragma once
// The models the mesh tests (vertex cache order, runs) measure on: the shipped robot
// and, where ../shared is beside the repository, CesiumMan, Duck and DamagedHelmet.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "asset/gltf_loader.h"
#include "asset/vertex_cache.h"

namespace engine::test {

// Calls visit(path, primitive) for every triangle list of those models that may be
// reordered (opaque); returns how many of the models were found.
template <typename Visit>
int forEachReorderableList(Visit visit) {
  const std::string shared = std::string(ENGINE_SOURCE_DIR) + "/../shared/";
  int models = 0;
  for (const std::string& path :
       {std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf",
        shared + "conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb", shared + "gltf-samples/Duck/glTF-Binary/Duck.glb",
        shared + "gltf-samples/DamagedHelmet/glTF-Binary/DamagedHelmet.glb"}) {
    if (!std::filesystem::exists(path)) continue;
    ++models;
    auto model = loadGltf(path);
    EXPECT_TRUE(model) << model.error().message;
    if (!model) continue;
    for (const MeshData& mesh : model->meshes)
      for (const PrimitiveData& p : mesh.primitives)
        if (mayReorderTriangles(*model, p)) visit(path, p);
  }
  return models;
}

}  // namespace engine::test
