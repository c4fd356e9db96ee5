// Meshes: each primitive's attributes, indices, morph targets and skin weights
// (compressed ones were decoded when parsing), the tangents and uv sets their
// materials need, and the meshes' default morph weights.
#include <algorithm>
#include <cmath>
#include <set>

#include "asset/gltf_loader_impl.h"
#include "asset/material_variants.h"
#include "asset/tangents.h"

namespace engine::gltf_loader {

// Normal maps and anisotropy need tangents: primitives without TANGENT get
// generated ones, as glTF asks; without NORMAL or TEXCOORD_0 there is nothing to
// build them from, and the primitive is drawn without its normal map (or stretch).
void Converter::addMissingTangents(PrimitiveData& prim, const std::string& name) {
  if (prim.material < 0 || !prim.tangents.empty()) return;
  const MaterialData& material = out_.materials[static_cast<std::size_t>(prim.material)];
  const TextureSlot slot = material.normalImage >= 0                                ? TextureSlot::Normal
                           : material.image(TextureSlot::ClearcoatNormal) >= 0     ? TextureSlot::ClearcoatNormal
                           : material.image(TextureSlot::Anisotropy) >= 0          ? TextureSlot::Anisotropy
                                                                                    : TextureSlot::BaseColor;
  if (slot == TextureSlot::BaseColor && material.layers.anisotropy <= 0.0f) return;
  const bool set1 = material.texture(slot).texCoord == 1;
  const std::vector<glm::vec2>& uvs = set1 ? prim.uvs1 : prim.uvs;
  if (prim.normals.empty() || uvs.empty() || prim.mode != 4) {
    const char* what = slot == TextureSlot::Normal || slot == TextureSlot::ClearcoatNormal ? "a normal map" : "anisotropy";
    warn(name + ": " + what + " needs NORMAL, TEXCOORD_" + (set1 ? "1" : "0") +
         " and triangles to build tangents; drawn without it");
    return;
  }
  prim.tangents = generateTangents(prim.positions, prim.normals, uvs, prim.indices);
}

// A material texture that reads TEXCOORD_1 on a primitive without it: a warning
// naming the primitive, the material and the slot, and set 0 is read instead
// (copied into uvs1, so that every renderer finds the set it asks for).
void Converter::checkUvSets(PrimitiveData& prim, const std::string& name) {
  if (prim.material < 0 || !prim.uvs1.empty()) return;
  const MaterialData& m = out_.materials[static_cast<std::size_t>(prim.material)];
  const std::string material = "material " + str(prim.material) + (m.name.empty() ? "" : " (\"" + m.name + "\")");
  bool needed = false;
  for (int i = 0; i < kTextureSlots; ++i) {
    if (m.image(TextureSlot(i)) < 0 || m.textures[std::size_t(i)].texCoord != 1) continue;
    warn(name + ": " + material + ": " + textureSlotName(TextureSlot(i)) + " reads TEXCOORD_1, which the primitive does not have; TEXCOORD_0 is used");
    needed = true;
  }
  if (needed) prim.uvs1 = prim.uvs;
}

// Reads an attribute that must have `components` per element and `count`
// elements (0 = any), as floats.
Result<std::vector<float>> Converter::readFloats(int accessor, int components, std::size_t count,
                                                 const std::string& context) {
  auto values = readAccessor(gltf_, accessor, file_ + ": " + context);
  if (!values) return values.error();
  if (values->components != components)
    return error(context + ": expected " + str(components) + " components per element, got " +
                 str(values->components));
  if (count != 0 && values->count != count)
    return error(context + ": has " + str(values->count) + " elements, expected " + str(count));
  std::vector<float> out(values->values.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<float>(values->values[i]);
    if (!std::isfinite(out[i])) return error(context + ": element " + str(i / static_cast<std::size_t>(components)) + " is NaN or infinite");
  }
  return out;
}

template <typename Vec>
std::vector<Vec> Converter::toVectors(const std::vector<float>& flat) {
  constexpr int n = Vec::length();
  std::vector<Vec> out(flat.size() / n);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < n; ++c) out[i][c] = flat[i * n + static_cast<std::size_t>(c)];
  return out;
}

Status Converter::convertMeshes() {
  for (std::size_t m = 0; m < gltf_.meshes.size(); ++m) {
    MeshData mesh;
    mesh.name = gltf_.meshes[m].name;
    for (std::size_t p = 0; p < gltf_.meshes[m].primitives.size(); ++p) {
      PrimitiveData prim;
      std::string name = "mesh " + str(m) + " primitive " + str(p);
      if (Status s = convertPrimitive(gltf_.meshes[m].primitives[p], prim, name); !s) return s;
      mesh.primitives.push_back(std::move(prim));
    }
    if (Status s = readMeshWeights(gltf_.meshes[m], mesh, "mesh " + str(m)); !s) return s;
    out_.meshes.push_back(std::move(mesh));
  }
  return Ok{};
}

int Converter::targetCount(const MeshData& mesh) {
  return mesh.primitives.empty() ? 0 : mesh.primitives.front().morphTargets;
}

// glTF requires the same number of targets in every primitive of a mesh, since
// one list of weights drives them all; `weights`, when given, has one per target.
Status Converter::readMeshWeights(const tinygltf::Mesh& src, MeshData& mesh, const std::string& name) {
  const int targets = targetCount(mesh);
  for (std::size_t p = 1; p < mesh.primitives.size(); ++p)
    if (mesh.primitives[p].morphTargets != targets)
      return error(name + ": primitive " + str(p) + " has " + str(mesh.primitives[p].morphTargets) +
                   " morph targets, primitive 0 has " + str(targets) + " (every primitive needs the same number)");
  auto weights = readWeightList(src.weights, targets, name);
  if (!weights) return weights.error();
  mesh.morphWeights = std::move(weights).value();
  return Ok{};
}

// KHR_materials_variants (asset/material_variants.h). A primitive drawn with a
// variant's material gets what that material needs too: tangents for its normal
// map, TEXCOORD_1 (or set 0 in its place) for its textures.
Status Converter::convertVariants() {
  if (Status s = readMaterialVariants(gltf_, file_, out_); !s) return s;
  for (std::size_t m = 0; m < out_.meshes.size(); ++m) {
    for (std::size_t p = 0; p < out_.meshes[m].primitives.size(); ++p) {
      PrimitiveData& prim = out_.meshes[m].primitives[p];
      const int own = prim.material;
      for (const int material : prim.variantMaterials) {
        if (material < 0 || material == own) continue;
        prim.material = material;
        const std::string name = "mesh " + str(m) + " primitive " + str(p);
        checkUvSets(prim, name);
        addMissingTangents(prim, name);
      }
      prim.material = own;
    }
  }
  return Ok{};
}

// A mesh's or node's `weights`: one finite number per morph target; an absent
// list is all zeros.
Result<std::vector<float>> Converter::readWeightList(const std::vector<double>& src, int targets, const std::string& name) const {
  if (src.empty()) return std::vector<float>(static_cast<std::size_t>(targets), 0.0f);
  if (src.size() != static_cast<std::size_t>(targets))
    return error(name + ": weights has " + str(src.size()) + " entries for " + str(targets) + " morph targets");
  std::vector<float> out;
  for (std::size_t i = 0; i < src.size(); ++i) {
    if (!std::isfinite(src[i])) return error(name + ": weights entry " + str(i) + " is NaN or infinite");
    out.push_back(static_cast<float>(src[i]));
  }
  return out;
}

int Converter::attribute(const tinygltf::Primitive& src, const char* name) {
  auto it = src.attributes.find(name);
  return it == src.attributes.end() ? -1 : it->second;
}

Status Converter::convertPrimitive(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
  int position = attribute(src, "POSITION");
  if (position < 0) return error(name + ": has no POSITION");
  auto positions = readFloats(position, 3, 0, name + " POSITION");
  if (!positions) return positions.error();
  prim.positions = toVectors<glm::vec3>(*positions);
  std::size_t count = prim.positions.size();
  if (int a = attribute(src, "NORMAL"); a >= 0) {
    auto v = readFloats(a, 3, count, name + " NORMAL");
    if (!v) return v.error();
    prim.normals = toVectors<glm::vec3>(*v);
  }
  if (int a = attribute(src, "TEXCOORD_0"); a >= 0) {
    auto v = readFloats(a, 2, count, name + " TEXCOORD_0");
    if (!v) return v.error();
    prim.uvs = toVectors<glm::vec2>(*v);
  }
  if (int a = attribute(src, "TEXCOORD_1"); a >= 0) {
    auto v = readFloats(a, 2, count, name + " TEXCOORD_1");
    if (!v) return v.error();
    prim.uvs1 = toVectors<glm::vec2>(*v);
  }
  if (Status s = readVertexColors(src, prim, name); !s) return s;
  if (int a = attribute(src, "TANGENT"); a >= 0) {
    auto v = readFloats(a, 4, count, name + " TANGENT");
    if (!v) return v.error();
    prim.tangents = toVectors<glm::vec4>(*v);
  }
  if (Status s = readMorphTargets(src, prim, name); !s) return s;
  if (src.material != -1 && !validIndex(src.material, out_.materials.size()))
    return error(name + ": material " + str(src.material) + " does not exist");
  prim.material = src.material;
  prim.mode = src.mode < 0 ? 4 : src.mode;
  if (Status s = readIndices(src, prim, name); !s) return s;
  checkUvSets(prim, name);
  addMissingTangents(prim, name);
  return readSkinAttributes(src, prim, name);
}

// COLOR_0: VEC3 or VEC4, float or normalized unsigned byte/short (readAccessor
// maps those to 0..1), one per vertex. RGB gets alpha 1. Sets past COLOR_0 are
// for the application, as glTF says, and are not read.
Status Converter::readVertexColors(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
  const int a = attribute(src, "COLOR_0");
  if (a < 0) return Ok{};
  const std::string where = name + " COLOR_0";
  if (!validIndex(a, gltf_.accessors.size())) return error(where + ": accessor " + str(a) + " does not exist");
  const int type = gltf_.accessors[static_cast<std::size_t>(a)].type;
  if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4) return error(where + ": must be VEC3 or VEC4");
  const int components = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
  auto v = readFloats(a, components, prim.positions.size(), where);
  if (!v) return v.error();
  prim.colors.resize(prim.positions.size());
  for (std::size_t i = 0; i < prim.colors.size(); ++i) {
    const float* c = v->data() + i * static_cast<std::size_t>(components);
    prim.colors[i] = glm::vec4(c[0], c[1], c[2], components == 4 ? c[3] : 1.0f);
  }
  return Ok{};
}

// The displacements of POSITION, NORMAL and TANGENT (glTF morphs no others;
// TEXCOORD_n and COLOR_n targets are warned about and ignored), each VEC3 with
// one element per vertex. Read before tangents are generated: a target may only
// move an attribute the file itself gives.
Status Converter::readMorphTargets(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
  if (src.targets.empty()) return Ok{};
  const std::size_t count = prim.positions.size();
  const std::size_t targets = src.targets.size();
  if (targets * count > kMaxMorphDeltas)
    return error(name + ": " + str(targets) + " morph targets of " + str(count) + " vertices, the limit is " +
                 str(kMaxMorphDeltas) + " displacements");
  prim.morphTargets = static_cast<int>(targets);
  std::set<std::string> ignored;
  for (std::size_t t = 0; t < targets; ++t) {
    for (const auto& [attribute, accessor] : src.targets[t]) {
      std::vector<glm::vec3>* deltas = morphDeltas(prim, attribute);
      if (deltas == nullptr) {
        ignored.insert(attribute);
        continue;
      }
      const std::string where = name + " target " + str(t) + " " + attribute;
      auto values = readFloats(accessor, 3, count, where);
      if (!values) return values.error();
      if (deltas->empty()) deltas->assign(targets * count, glm::vec3(0.0f));
      const auto vectors = toVectors<glm::vec3>(*values);
      std::copy(vectors.begin(), vectors.end(), deltas->begin() + static_cast<std::ptrdiff_t>(t * count));
    }
  }
  if (!ignored.empty())
    warn(name + ": morph targets of " + joined(std::vector<std::string>(ignored.begin(), ignored.end())) +
         " are ignored (POSITION is morphed, and NORMAL and TANGENT where the primitive has them)");
  return Ok{};
}

// Where a target's displacements of `attribute` go, or nullptr when this engine
// does not morph it (or the primitive lacks the attribute they would move).
std::vector<glm::vec3>* Converter::morphDeltas(PrimitiveData& prim, const std::string& attribute) {
  if (attribute == "POSITION") return &prim.morphPositions;
  if (attribute == "NORMAL" && !prim.normals.empty()) return &prim.morphNormals;
  if (attribute == "TANGENT" && !prim.tangents.empty()) return &prim.morphTangents;
  return nullptr;
}

Status Converter::readIndices(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
  if (src.indices < 0) return Ok{};
  auto values = readAccessor(gltf_, src.indices, file_ + ": " + name + " indices");
  if (!values) return values.error();
  if (values->components != 1) return error(name + " indices: must be SCALAR");
  prim.indices.resize(values->count);
  for (std::size_t i = 0; i < values->count; ++i) {
    double v = values->values[i];
    if (!(v >= 0.0) || v >= static_cast<double>(prim.positions.size()))
      return error(name + " indices: index " + str(i) + " = " + std::to_string(v) +
                   " is past the " + str(prim.positions.size()) + " vertices");
    prim.indices[i] = static_cast<std::uint32_t>(v);
  }
  return Ok{};
}

Status Converter::readSkinAttributes(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name) {
  int sets = 0;
  for (int set = 0; set < 2; ++set) {
    std::string suffix = "_" + str(set);
    bool hasJoints = attribute(src, ("JOINTS" + suffix).c_str()) >= 0;
    bool hasWeights = attribute(src, ("WEIGHTS" + suffix).c_str()) >= 0;
    if (hasJoints != hasWeights) return error(name + ": JOINTS" + suffix + " and WEIGHTS" + suffix + " must come together");
    if (!hasJoints) break;
    sets = set + 1;
  }
  if (sets == 0) return Ok{};
  std::size_t count = prim.positions.size();
  prim.influences = sets * 4;
  std::size_t stride = static_cast<std::size_t>(prim.influences);
  prim.joints.assign(count * stride, 0);
  prim.weights.assign(count * stride, 0.0f);
  for (int set = 0; set < sets; ++set) {
    std::string jointsName = name + " JOINTS_" + str(set);
    auto joints = readAccessor(gltf_, attribute(src, ("JOINTS_" + str(set)).c_str()), file_ + ": " + jointsName);
    if (!joints) return joints.error();
    if (joints->components != 4 || joints->count != count)
      return error(jointsName + ": must be VEC4 with one element per vertex");
    auto weights = readFloats(attribute(src, ("WEIGHTS_" + str(set)).c_str()), 4, count, name + " WEIGHTS_" + str(set));
    if (!weights) return weights.error();
    for (std::size_t v = 0; v < count; ++v)
      for (std::size_t k = 0; k < 4; ++k) {
        double j = joints->values[v * 4 + k];
        if (!(j >= 0.0) || j > 65535.0) return error(jointsName + ": vertex " + str(v) + " has joint " + std::to_string(j));
        float w = (*weights)[v * 4 + k];
        if (w < 0.0f) return error(name + " WEIGHTS_" + str(set) + ": vertex " + str(v) + " has a negative weight");
        prim.joints[v * stride + static_cast<std::size_t>(set) * 4 + k] = static_cast<std::uint16_t>(j);
        prim.weights[v * stride + static_cast<std::size_t>(set) * 4 + k] = w;
      }
  }
  normaliseWeights(prim);
  return Ok{};
}

// Exporters often write weights that sum to 0.999 or 1.01; skinning assumes 1.
// An all-zero vertex follows its first joint, as three.js does.
void Converter::normaliseWeights(PrimitiveData& prim) {
  std::size_t stride = static_cast<std::size_t>(prim.influences);
  for (std::size_t v = 0; v < prim.positions.size(); ++v) {
    float* w = &prim.weights[v * stride];
    float sum = 0.0f;
    for (std::size_t k = 0; k < stride; ++k) sum += w[k];
    if (sum > 0.0f) {
      for (std::size_t k = 0; k < stride; ++k) w[k] /= sum;
    } else {
      w[0] = 1.0f;
    }
  }
}

}  // namespace engine::gltf_loader
