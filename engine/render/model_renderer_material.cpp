// A glTF material on the GPU: its uniforms for both shading models, its uv
// transforms and its textures with their samplers.
#include <array>
#include <string>

#include "gl/bindings.h"
#include "render/model_renderer_impl.h"

namespace engine {
namespace {

// Texture units of common/material.glsl (gl/bindings.h), by TextureSlot.
constexpr GLuint kSlotUnits[kTextureSlots] = {gl::binding::kBaseColor,       gl::binding::kNormal,
                                              gl::binding::kMetallicRoughness, gl::binding::kEmissive,
                                              gl::binding::kOcclusion,         gl::binding::kSpecular,
                                              gl::binding::kSpecularColor,     gl::binding::kClearcoat,
                                              gl::binding::kClearcoatRoughness, gl::binding::kTransmission,
                                              gl::binding::kThickness,         gl::binding::kClearcoatNormal,
                                              gl::binding::kSheenColor,        gl::binding::kSheenRoughness,
                                              gl::binding::kAnisotropy,        gl::binding::kIridescence,
                                              gl::binding::kIridescenceThickness};

// Binds each sampled slot's image (colour slots as sRGB) and its glTF sampler, and
// a sheen's albedo table.
void bindMaterialTextures(const GpuModel& gpu, const MaterialData& m, const ShaderVariant& v) {
  if (v.sheen) gpu.sheenAlbedo().bind(gl::binding::kSheenAlbedo);
  const auto sampled = sampledSlots(v, m);
  for (int i = 0; i < kTextureSlots; ++i) {
    if (!sampled[size_t(i)]) continue;
    const TextureSlot slot = TextureSlot(i);
    gpu.image(m.image(slot), isSrgbSlot(slot)).bind(kSlotUnits[i]);
    gpu.sampler(m.textures[size_t(i)].sampler).bind(kSlotUnits[i]);
  }
}

}  // namespace

// The classic model's highlight weight for a glTF material: its roughness turned into
// a Blinn-Phong highlight, none at roughness 1.
float classicSpecular(const MaterialData* material) {
  return 0.5f * (1.0f - (material ? material->roughnessFactor : 1.0f));
}

// glTF's material for both shading models: PBR reads metallic and roughness; the
// classic model turns roughness into a Blinn-Phong highlight.
void setMaterialUniforms(const gl::Program& pr, const MaterialData* material) {
  const float roughness = material ? material->roughnessFactor : 1.0f;
  pr.set("u_baseColorFactor", material ? material->baseColorFactor : glm::vec4(1.0f));
  pr.set("u_metallic", material ? material->metallicFactor : 0.0f);
  pr.set("u_roughness", roughness);
  pr.set("u_emissive", material ? material->emissiveFactor : glm::vec3(0.0f));
  pr.set("u_ambient", 0.1f);
  pr.set("u_diffuse", 0.9f);
  pr.set("u_specular", classicSpecular(material));
  pr.set("u_shininess", 32.0f);
  pr.set("u_reflection", 0.0f);
  if (!material) return;
  if (material->layered()) {
    const MaterialLayers& l = material->layers;
    pr.set("u_iorF0", l.iorF0());
    pr.set("u_specularWeight", l.specular);
    pr.set("u_specularColor", l.specularColor);
    pr.set("u_clearcoat", l.clearcoat);
    pr.set("u_clearcoatRoughness", l.clearcoatRoughness);
    pr.set("u_transmission", l.transmission);
    pr.set("u_thickness", l.thickness);
    pr.set("u_ior", l.ior);
    pr.set("u_attenuationDistance", l.attenuationDistance);
    pr.set("u_attenuationColor", l.attenuationColor);
    pr.set("u_clearcoatNormalScale", l.clearcoatNormalScale);
    pr.set("u_sheenColor", l.sheenColor);
    pr.set("u_sheenRoughness", l.sheenRoughness);
    pr.set("u_anisotropy", l.anisotropy);
    pr.set("u_anisotropyRotation", l.anisotropyRotation);
    pr.set("u_iridescence", l.iridescence);
    pr.set("u_iridescenceIor", l.iridescenceIor);
    pr.set("u_iridescenceThickness", glm::vec2(l.iridescenceThicknessMin, l.iridescenceThicknessMax));
  }
  pr.set("u_normalScale", material->normalScale);
  pr.set("u_occlusionStrength", material->occlusionStrength);
  pr.set("u_alphaCutoff", material->alphaCutoff);
}

// Each slot's uv set and KHR_texture_transform matrix, for UV_TRANSFORM variants.
void setUvTransforms(const gl::Program& pr, const MaterialData& m) {
  using Names = std::array<std::string, kTextureSlots>;
  auto names = [](const char* array) {
    Names out;
    for (int i = 0; i < kTextureSlots; ++i) out[size_t(i)] = std::string(array) + "[" + std::to_string(i) + "]";
    return out;
  };
  static const Names kTransforms = names("u_uvTransform"), kTexCoords = names("u_texCoord");
  for (size_t i = 0; i < size_t(kTextureSlots); ++i) {
    pr.set(kTransforms[i].c_str(), m.textures[i].uvTransform);
    pr.set(kTexCoords[i].c_str(), m.textures[i].texCoord);
  }
}

// Which slots the variant samples: the layer textures the material has, in a
// +layertextures variant (common/material.glsl's u_layerTextures says which).
std::array<bool, kTextureSlots> sampledSlots(const ShaderVariant& v, const MaterialData& m) {
  std::array<bool, kTextureSlots> sampled{v.textured, v.normalMap, v.metallicRoughnessTexture, v.emissiveTexture,
                                          v.occlusion};
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) sampled[size_t(i)] = v.layerTextures && m.image(TextureSlot(i)) >= 0;
  return sampled;
}

// Bit i - kFirstLayerSlot: layer slot i has a texture (common/material.glsl).
int layerTextureMask(const MaterialData& m) {
  int mask = 0;
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) mask |= m.image(TextureSlot(i)) >= 0 ? 1 << (i - kFirstLayerSlot) : 0;
  return mask;
}

// The material's textures, or for glTF's default material (none) the white base
// colour where the variant shades.
void bindMaterialOrWhite(const GpuModel& gpu, const MaterialData* m, const ShaderVariant& v) {
  if (m) {
    bindMaterialTextures(gpu, *m, v);
  } else if (!v.depthOnly) {
    gpu.image(-1, true).bind(gl::binding::kBaseColor);
  }
}

// The units' own texture parameters again, for whatever draws next (the scene's
// shapes and terrain bind textures on the same units without samplers).
void unbindMaterialSamplers(const ShaderVariant& v, const MaterialData& m) {
  const auto sampled = sampledSlots(v, m);
  for (int i = 0; i < kTextureSlots; ++i)
    if (sampled[size_t(i)]) gl::Sampler::unbind(kSlotUnits[i]);
}

const MaterialData* materialOf(const ModelData& model, int material) {
  return material >= 0 && material < int(model.materials.size()) ? &model.materials[size_t(material)] : nullptr;
}

}  // namespace engine
