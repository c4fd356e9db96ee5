#include "gputrace/gpu_materials.h"

namespace engine::gpurt {

std::vector<GpuMaterial> materialsOf(const rt::RtScene& scene, const rt::GpuTextureSet& textures) {
  std::vector<GpuMaterial> out;
  for (std::size_t i = 0; i < scene.materials().size(); ++i) {
    const rt::HitMaterial m = scene.baseMaterial(int(i));
    const rt::RtScene::MaterialExtras& e = scene.extras(int(i));
    const MaterialLayers& layers = scene.materials()[i].layers;
    const float alphaMode = e.alphaMode == AlphaMode::Mask ? 1.0f : e.alphaMode == AlphaMode::Blend ? 2.0f : 0.0f;
    out.push_back(GpuMaterial{glm::vec4(m.albedo, m.ambient), glm::vec4(m.diffuse, m.specular, m.shininess, m.reflection),
                              glm::vec4(m.metallic, m.roughness, m.unlit ? 1.0f : 0.0f, 0.0f), glm::vec4(m.emission, 0.0f),
                              glm::vec4(m.dielectricF0, m.dielectricF90),
                              glm::ivec4(e.texture, e.metallicRoughnessTexture, e.emissiveTexture, e.terrain),
                              glm::vec4(scene.materials()[i].textureScale, e.readsUv() ? 1.0f : 0.0f, 0.0f, 0.0f),
                              glm::vec4(alphaMode, e.alpha, e.alphaCutoff, e.singleSided ? 1.0f : 0.0f),
                              glm::vec4(m.clearcoat, m.clearcoatRoughness, m.sheenRoughness, m.iridescence),
                              glm::vec4(m.sheenColor, m.iridescenceIor), glm::vec4(m.iridescenceThickness, 0.0f, 0.0f, 0.0f),
                              glm::vec4(m.transmission, m.ior, m.thickness, m.attenuationDistance),
                              glm::vec4(m.attenuationColor, 0.0f),
                              glm::vec4(m.anisotropy, m.anisotropyRotation, m.anisotropyDirection),
                              glm::ivec4(-1), glm::dvec2(0.0), {},
                              glm::vec4(layers.specularColor, layers.specular),
                              glm::vec4(layers.iridescenceThicknessMin, layers.iridescenceThicknessMax, 0.0f, 0.0f),
                              glm::dvec2(layers.reflectance(), 0.0)});
    GpuMaterial& g = out.back();
    for (std::size_t k = 0; k < e.layerTextures.size(); ++k) g.layerTextures[k / 4][int(k % 4)] = e.layerTextures[k];
    if (e.terrain >= 0) {
      const rt::GpuTerrain& t = textures.terrains[std::size_t(e.terrain)];
      g.terrainLayers = t.layers;
      g.terrainOriginYHeightScale = t.originYHeightScale;
    }
  }
  return out;
}

}  // namespace engine::gpurt
