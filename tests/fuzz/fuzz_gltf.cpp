// glTF / GLB bytes -> engine::ModelData through the loader's in-memory entry point
// (the same code path as loadGltf after the file is read). The input is named
// .gltf, so the magic alone decides whether it is read as GLB. Any input must give
// either a model whose invariants hold or an error naming the input; never a crash,
// a sanitizer report or an out-of-memory.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "asset/gltf_loader.h"
#include "fuzz_support.h"

namespace {

// The promises model_data.h makes to anim and render: check them, so that a
// loader change that lets a bad index through shows up as a crash here.
void checkInvariants(const engine::ModelData& m) {
  const auto nodeCount = static_cast<int>(m.nodes.size());
  for (const auto& node : m.nodes) {
    if (node.parent < -1 || node.parent >= nodeCount) std::abort();
    if (node.mesh < -1 || node.mesh >= static_cast<int>(m.meshes.size())) std::abort();
    if (node.skin < -1 || node.skin >= static_cast<int>(m.skins.size())) std::abort();
    for (int c : node.children)
      if (c < 0 || c >= nodeCount) std::abort();
  }
  for (const auto& mesh : m.meshes)
    for (const auto& prim : mesh.primitives) {
      for (std::uint32_t i : prim.indices)
        if (i >= prim.positions.size()) std::abort();
      const std::size_t k = static_cast<std::size_t>(prim.influences);
      if (prim.joints.size() != prim.positions.size() * k || prim.weights.size() != prim.joints.size()) std::abort();
      if (prim.material < -1 || prim.material >= static_cast<int>(m.materials.size())) std::abort();
    }
  for (const auto& skin : m.skins) {
    if (skin.inverseBinds.size() != skin.joints.size()) std::abort();
    for (int j : skin.joints)
      if (j < 0 || j >= nodeCount) std::abort();
  }
  for (const auto& image : m.images)
    if (image.image.pixels.size() != static_cast<std::size_t>(image.image.width) * image.image.height * 4)
      std::abort();
  for (const auto& anim : m.animations)
    for (const auto& ch : anim.channels) {
      if (ch.node < 0 || ch.node >= nodeCount || ch.times.empty()) std::abort();
      for (std::size_t k = 1; k < ch.times.size(); ++k)
        if (!(ch.times[k] >= ch.times[k - 1])) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::quietLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto model = engine::loadGltfFromMemory(std::span(data, size), "fuzz.gltf");
  if (model) {
    checkInvariants(*model);
  } else if (model.error().message.rfind("fuzz.gltf: ", 0) != 0) {
    std::abort();  // every error names the file
  }
  return 0;
}
