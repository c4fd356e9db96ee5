#pragma once
// KHR_materials_variants: a file's named sets of materials (a shoe in three
// colours), each primitive mapping some variants to a material of its own. The
// loader reads them (ModelData::variants, PrimitiveData::variantMaterials); a model
// is drawn as one variant by remapping its primitives' materials before it becomes
// an asset, so that every renderer sees plain materials.
#include <optional>
#include <string>

#include "asset/model_data.h"
#include "core/result.h"

namespace tinygltf {
class Model;
}

namespace engine {

// Reads the root's variant names and each primitive's mappings into `out` (whose
// meshes and materials are already converted, primitive for primitive). Errors name
// the file, the mesh, the primitive and the mapping.
Status readMaterialVariants(const tinygltf::Model& gltf, const std::string& file, ModelData& out);

// The variant `nameOrIndex` names: a variant's name, else its index as a number;
// nullopt when it names none.
std::optional<int> findVariant(const ModelData& model, const std::string& nameOrIndex);

// `model` with every primitive's material that of `variant` (-1: the file's default
// materials, as loaded).
ModelData withVariant(const ModelData& model, int variant);

}  // namespace engine
