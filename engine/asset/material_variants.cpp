#include "asset/material_variants.h"

#include <tiny_gltf.h>

namespace engine {
namespace {

std::string str(std::size_t n) { return std::to_string(n); }

// One primitive's "mappings": each a material and the variants that use it.
Status readMappings(const tinygltf::Value& ext, const std::string& where, std::size_t materials, PrimitiveData& prim) {
  const std::size_t variants = prim.variantMaterials.size();
  if (!ext.IsObject() || !ext.Has("mappings") || !ext.Get("mappings").IsArray())
    return makeError(where + ": needs a \"mappings\" list");
  const tinygltf::Value& mappings = ext.Get("mappings");
  for (std::size_t m = 0; m < mappings.ArrayLen(); ++m) {
    const tinygltf::Value& mapping = mappings.Get(int(m));
    const std::string at = where + ": mapping " + str(m);
    if (!mapping.IsObject() || !mapping.Has("material") || !mapping.Get("material").IsInt() ||
        !mapping.Has("variants") || !mapping.Get("variants").IsArray())
      return makeError(at + ": needs a \"material\" index and a \"variants\" list");
    const int material = mapping.Get("material").GetNumberAsInt();
    if (material < 0 || std::size_t(material) >= materials)
      return makeError(at + ": material " + std::to_string(material) + " does not exist (" + str(materials) + " materials)");
    const tinygltf::Value& list = mapping.Get("variants");
    for (std::size_t v = 0; v < list.ArrayLen(); ++v) {
      const int variant = list.Get(int(v)).IsInt() ? list.Get(int(v)).GetNumberAsInt() : -1;
      if (variant < 0 || std::size_t(variant) >= variants)
        return makeError(at + ": variant " + (list.Get(int(v)).IsInt() ? std::to_string(variant) : std::string("?")) +
                         " does not exist (" + str(variants) + " variants)");
      prim.variantMaterials[std::size_t(variant)] = material;
    }
  }
  return Ok{};
}

}  // namespace

Status readMaterialVariants(const tinygltf::Model& gltf, const std::string& file, ModelData& out) {
  auto root = gltf.extensions.find("KHR_materials_variants");
  if (root != gltf.extensions.end()) {
    const tinygltf::Value& list = root->second.Get("variants");
    if (!root->second.IsObject() || !list.IsArray())
      return makeError(file + ": KHR_materials_variants: needs a \"variants\" list");
    for (std::size_t v = 0; v < list.ArrayLen(); ++v) {
      const tinygltf::Value& variant = list.Get(int(v));
      if (!variant.IsObject() || !variant.Has("name") || !variant.Get("name").IsString())
        return makeError(file + ": KHR_materials_variants: variant " + str(v) + " needs a name");
      out.variants.push_back(variant.Get("name").Get<std::string>());
    }
  }
  for (std::size_t m = 0; m < gltf.meshes.size() && m < out.meshes.size(); ++m) {
    for (std::size_t p = 0; p < gltf.meshes[m].primitives.size() && p < out.meshes[m].primitives.size(); ++p) {
      auto ext = gltf.meshes[m].primitives[p].extensions.find("KHR_materials_variants");
      if (ext == gltf.meshes[m].primitives[p].extensions.end()) continue;
      const std::string where = file + ": mesh " + str(m) + " primitive " + str(p) + ": KHR_materials_variants";
      if (out.variants.empty()) return makeError(where + ": the file declares no variants");
      PrimitiveData& prim = out.meshes[m].primitives[p];
      prim.variantMaterials.assign(out.variants.size(), -1);
      if (Status s = readMappings(ext->second, where, out.materials.size(), prim); !s) return s;
    }
  }
  return Ok{};
}

std::optional<int> findVariant(const ModelData& model, const std::string& nameOrIndex) {
  for (std::size_t v = 0; v < model.variants.size(); ++v)
    if (model.variants[v] == nameOrIndex) return int(v);
  if (nameOrIndex.empty() || nameOrIndex.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const unsigned long index = std::stoul(nameOrIndex.substr(0, 9));
  return index < model.variants.size() ? std::optional<int>(int(index)) : std::nullopt;
}

ModelData withVariant(const ModelData& model, int variant) {
  ModelData out = model;
  if (variant < 0) return out;
  for (MeshData& mesh : out.meshes) {
    for (PrimitiveData& prim : mesh.primitives) {
      if (std::size_t(variant) < prim.variantMaterials.size() && prim.variantMaterials[std::size_t(variant)] >= 0)
        prim.material = prim.variantMaterials[std::size_t(variant)];
    }
  }
  return out;
}

}  // namespace engine
