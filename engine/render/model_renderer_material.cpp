// A glTF material on the GPU: its uniforms for both shading models, its uv
// transforms and its textures with their samplers.
#include <array>
#include <string>

#include "gl/bindings.h"
#include "render/material_uniforms.h"
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
void bindMaterialTextures(const GpuModel& gpu, const SceneMaterial& m, const ShaderVariant& v) {
  if (v.sheen) gpu.sheenAlbedo().bind(gl::binding::kSheenAlbedo);
  const auto sampled = sampledSlots(v, presentSlots(m));
  for (int i = 0; i < kTextureSlots; ++i) {
    if (!sampled[size_t(i)]) continue;
    const TextureSlot slot = TextureSlot(i);
    gpu.image(m.texture(slot).image, isSrgbSlot(slot)).bind(kSlotUnits[i]);
    gpu.sampler(m.texture(slot).sampling.sampler).bind(kSlotUnits[i]);
  }
}

}  // namespace

// The scene layer's material (scene/materials.h) for both shading models: the one
// translation of glTF's metallic-roughness the tracers read too.
void setMaterialUniforms(const gl::Program& pr, const SceneMaterial& material) {
  forEachMaterialUniform(material, [&](const char* name, const auto& value) { pr.set(name, value); });
}

// Each slot's uv set and KHR_texture_transform matrix, for UV_TRANSFORM variants.
void setUvTransforms(const gl::Program& pr, const SceneMaterial& m) {
  using Names = std::array<std::string, kTextureSlots>;
  auto names = [](const char* array) {
    Names out;
    for (int i = 0; i < kTextureSlots; ++i) out[size_t(i)] = std::string(array) + "[" + std::to_string(i) + "]";
    return out;
  };
  static const Names kTransforms = names("u_uvTransform"), kTexCoords = names("u_texCoord");
  for (size_t i = 0; i < size_t(kTextureSlots); ++i) {
    pr.set(kTransforms[i].c_str(), m.textures[i].sampling.uvTransform);
    pr.set(kTexCoords[i].c_str(), m.textures[i].sampling.texCoord);
  }
}

std::array<bool, kTextureSlots> presentSlots(const MaterialData& m) {
  std::array<bool, kTextureSlots> present{};
  for (int i = 0; i < kTextureSlots; ++i) present[size_t(i)] = m.image(TextureSlot(i)) >= 0;
  return present;
}

std::array<bool, kTextureSlots> presentSlots(const SceneMaterial& m) {
  std::array<bool, kTextureSlots> present{};
  for (int i = 0; i < kTextureSlots; ++i) present[size_t(i)] = m.textures[size_t(i)].present();
  return present;
}

// Which slots the variant samples: the layer textures the material has, in a
// +layertextures variant (common/material.glsl's u_layerTextures says which).
std::array<bool, kTextureSlots> sampledSlots(const ShaderVariant& v, const std::array<bool, kTextureSlots>& present) {
  std::array<bool, kTextureSlots> sampled{v.textured, v.normalMap, v.metallicRoughnessTexture, v.emissiveTexture,
                                          v.occlusion};
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) sampled[size_t(i)] = v.layerTextures && present[size_t(i)];
  return sampled;
}

// Bit i - kFirstLayerSlot: layer slot i has a texture (common/material.glsl).
int layerTextureMask(const SceneMaterial& m) {
  int mask = 0;
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) mask |= m.textures[size_t(i)].present() ? 1 << (i - kFirstLayerSlot) : 0;
  return mask;
}

// The material's textures, or for glTF's default material (none) the white base
// colour where the variant shades.
void bindMaterialOrWhite(const GpuModel& gpu, const SceneMaterial* m, const ShaderVariant& v) {
  if (m) {
    bindMaterialTextures(gpu, *m, v);
  } else if (!v.depthOnly) {
    gpu.image(-1, true).bind(gl::binding::kBaseColor);
  }
}

// The units' own texture parameters again, for whatever draws next (the scene's
// shapes and terrain bind textures on the same units without samplers).
void unbindMaterialSamplers(const ShaderVariant& v, const SceneMaterial& m) {
  const auto sampled = sampledSlots(v, presentSlots(m));
  for (int i = 0; i < kTextureSlots; ++i)
    if (sampled[size_t(i)]) gl::Sampler::unbind(kSlotUnits[i]);
}

const MaterialData* materialOf(const ModelData& model, int material) {
  return material >= 0 && material < int(model.materials.size()) ? &model.materials[size_t(material)] : nullptr;
}

}  // namespace engine
