#include "scene/materials.h"

#include "scene/scene_images.h"

namespace engine {

namespace {

// Slot `slot` of `material`: its image in `model` (decoded with the model) and its
// sampling. An index the loader let through out of range keeps its index (the
// rasterizer binds white for it) and no image.
MaterialTexture gltfTexture(const MaterialData& material, TextureSlot slot, const ModelData& model) {
  MaterialTexture t;
  t.image = material.image(slot);
  if (t.image >= 0 && t.image < int(model.images.size())) t.decoded = &model.images[std::size_t(t.image)].image;
  t.sampling = material.texture(slot);
  return t;
}

}  // namespace

SceneMaterial gltfMaterial(const MaterialData& material, const ModelData& model) {
  SceneMaterial out;
  MaterialDesc& s = out.surface;
  s.name = material.name;
  s.color = glm::vec3(material.baseColorFactor);
  s.metallic = material.metallicFactor;
  s.roughness = material.roughnessFactor;
  s.specular = classicSpecularOf(material.roughnessFactor);
  s.emission = material.emissiveFactor;
  s.layers = material.layers;
  out.alpha = material.baseColorFactor.a;
  out.alphaMode = material.alphaMode;
  out.alphaCutoff = material.alphaCutoff;
  out.doubleSided = material.doubleSided;
  out.unlit = material.unlit;
  out.normalScale = material.normalScale;
  out.occlusionStrength = material.occlusionStrength;
  out.layered = material.layered();
  out.origin = UvOrigin::TopLeft;
  for (int i = 0; i < kTextureSlots; ++i) out.textures[std::size_t(i)] = gltfTexture(material, TextureSlot(i), model);
  return out;
}

SceneMaterial gltfDefaultMaterial() {
  SceneMaterial out;
  out.surface.name = "glTF default";
  out.surface.color = glm::vec3(1.0f);
  out.surface.metallic = 0.0f;
  out.surface.roughness = 1.0f;
  out.surface.specular = classicSpecularOf(1.0f);
  return out;
}

std::vector<SceneMaterial> gltfMaterials(const ModelData& model) {
  std::vector<SceneMaterial> out;
  out.reserve(model.materials.size());
  for (const MaterialData& m : model.materials) out.push_back(gltfMaterial(m, model));
  return out;
}

const SceneMaterial& gltfMaterialOf(std::span<const SceneMaterial> table, int material) {
  static const SceneMaterial kDefault = gltfDefaultMaterial();
  return material >= 0 && material < int(table.size()) ? table[std::size_t(material)] : kDefault;
}

SceneMaterial sceneFileMaterial(const MaterialDesc& material, const Image* texture, int index) {
  SceneMaterial out;
  out.surface = material;
  out.doubleSided = true;
  out.origin = UvOrigin::BottomLeft;
  // The rasterizer draws no layer on a shape (layers are glTF's; a test may set them
  // on a scene material for the tracers alone).
  out.layered = false;
  if (texture) {
    MaterialTexture& base = out.textures[std::size_t(TextureSlot::BaseColor)];
    base.image = index;
    base.decoded = texture;
  }
  return out;
}

std::vector<SceneMaterial> sceneFileMaterials(const SceneDesc& desc, const SceneImages& images) {
  std::vector<SceneMaterial> out;
  out.reserve(desc.materials.size());
  for (std::size_t i = 0; i < desc.materials.size(); ++i)
    out.push_back(sceneFileMaterial(desc.materials[i], images.materialTexture(i), int(i)));
  return out;
}

}  // namespace engine
