#include "raytrace/rt_materials.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>


namespace engine::rt {

RtMaterials::RtMaterials() {
  MaterialDesc fallback;
  fallback.name = "default";
  materials_.push_back(fallback);
  extras_.emplace_back();
}

RtMaterials::RtMaterials(std::vector<MaterialDesc> materials)
    : materials_(std::move(materials)), extras_(materials_.size(), MaterialExtras{}) {}

int RtMaterials::addMaterial(const MaterialDesc& material) {
  materials_.push_back(material);
  extras_.emplace_back().dielectricF0 = material.layers.dielectricF0();
  return int(materials_.size() - 1);
}

Result<int> RtMaterials::addSceneMaterial(const SceneMaterial& material) {
  const int added = addMaterial(material.surface);
  if (auto s = setSceneMaterial(added, material); !s) return s.error();
  return added;
}

namespace {

// Slot `slot` of `m` as the tracers sample it: its decoded image from the row the
// table says uv v = 0 reads, in the slot's encoding, with its sampler's wrap, uv set
// and KHR_texture_transform.
RtTexture slotTexture(const SceneMaterial& m, TextureSlot slot) {
  const MaterialTexture& t = m.texture(slot);
  const TextureOrigin origin = m.origin == UvOrigin::TopLeft ? TextureOrigin::TopLeft : TextureOrigin::BottomLeft;
  RtTexture texture(*t.decoded, origin, isSrgbSlot(slot) ? TextureEncoding::Srgb : TextureEncoding::Linear);
  texture.setWrap(t.sampling.sampler.wrapS, t.sampling.sampler.wrapT).setMapping(t.sampling.texCoord, t.sampling.uvTransform);
  return texture;
}

// The slots the tracers sample beyond the base colour, emissive and
// metallic-roughness ones: every layer's but the coat's normal map.
bool tracedLayerSlot(int slot) { return slot >= kFirstLayerSlot && TextureSlot(slot) != TextureSlot::ClearcoatNormal; }

// The texel of textures[index] at uv (in `texel`), and whether there is one: an index
// below 0 is no texture. What the base and the layer texels both read by.
bool texelAt(const std::vector<RtTexture>& textures, int index, const HitUv& uv, float footprint, glm::vec4& texel) {
  if (index < 0) return false;
  texel = textures[size_t(index)].sampleRgba(uv, footprint);
  return true;
}

}  // namespace

Status RtMaterials::setSceneMaterial(int material, const SceneMaterial& from) {
  auto has = [&](TextureSlot slot) { return from.texture(slot).decoded != nullptr; };
  if (has(TextureSlot::BaseColor)) {
    if (auto s = setMaterialTexture(material, slotTexture(from, TextureSlot::BaseColor)); !s) return s;
  }
  if (has(TextureSlot::Emissive)) {
    if (auto s = setEmissiveTexture(material, slotTexture(from, TextureSlot::Emissive)); !s) return s;
  }
  if (has(TextureSlot::MetallicRoughness)) {
    if (auto s = setMetallicRoughnessTexture(material, slotTexture(from, TextureSlot::MetallicRoughness)); !s) return s;
  }
  for (int slot = kFirstLayerSlot; slot < kTextureSlots; ++slot) {
    if (!tracedLayerSlot(slot) || !has(TextureSlot(slot))) continue;
    if (auto s = setLayerTexture(material, TextureSlot(slot), slotTexture(from, TextureSlot(slot))); !s) return s;
  }
  if (auto s = setMaterialAlpha(material, from.alphaMode, from.alpha, from.alphaCutoff); !s) return s;
  if (auto s = setSingleSided(material, !from.doubleSided); !s) return s;
  return setUnlit(material, from.unlit);
}

Status RtMaterials::checkMaterial(int material) const {
  if (material < 0 || material >= int(materials_.size())) {
    return makeError("material " + std::to_string(material) + " out of range");
  }
  return Ok{};
}

// Stores the texture and points the material's `slot` at it.
Status RtMaterials::attachTexture(int material, int MaterialExtras::*slot, RtTexture texture) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].*slot = int(textures_.size());
  textures_.push_back(std::move(texture));
  return Ok{};
}

Status RtMaterials::setMaterialTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::texture, std::move(texture));
}

// The base colour, metallic-roughness and emissive texels at a hit, applied by the
// tracers' one text (core/layer_texels.h).
brdf::BaseValues RtMaterials::baseAt(int material, const HitUv& uv, float footprint) const {
  const MaterialDesc& m = materials_[size_t(material)];
  const MaterialExtras& e = extras_[size_t(material)];
  const int slots[3] = {e.texture, e.metallicRoughnessTexture, e.emissiveTexture};
  glm::vec4 texel[3] = {};
  bool present[3] = {};
  // Not through texelAt: written so, the loop took a third more instructions
  // (callgrind, the room).
  for (int k = 0; k < 3; ++k) {
    present[k] = slots[k] >= 0;
    if (present[k]) texel[k] = textures_[size_t(slots[k])].sampleRgba(uv, footprint);
  }
  brdf::BaseValues v;
  v.albedo = m.color;
  v.metallic = m.metallic;
  v.roughness = m.roughness;
  v.emission = m.emission;
  return brdf::withBaseTexels(v, glm::vec3(uv.color), texel, present);
}

Status RtMaterials::setMaterialAlpha(int material, AlphaMode mode, float factor, float cutoff) {
  if (auto s = checkMaterial(material); !s) return s.error();
  MaterialExtras& e = extras_[size_t(material)];
  e.alphaMode = mode;
  e.alpha = factor;
  e.alphaCutoff = cutoff;
  if (mode != AlphaMode::Opaque) transparent_ = true;
  return Ok{};
}

Status RtMaterials::setMetallicRoughnessTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::metallicRoughnessTexture, std::move(texture));
}

Status RtMaterials::setSingleSided(int material, bool singleSided) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].singleSided = singleSided;
  if (singleSided) singleSided_ = true;
  return Ok{};
}

Status RtMaterials::setUnlit(int material, bool unlit) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].unlit = unlit;
  return Ok{};
}

Status RtMaterials::setLayerTexture(int material, TextureSlot slot, RtTexture texture) {
  if (auto s = checkMaterial(material); !s) return s.error();
  if (int(slot) < kFirstLayerSlot || int(slot) >= kTextureSlots) return makeError("not a layer texture slot");
  MaterialExtras& e = extras_[size_t(material)];
  e.layerTextures[size_t(slot) - kFirstLayerSlot] = int(textures_.size());
  e.hasLayerTextures = true;
  textures_.push_back(std::move(texture));
  return Ok{};
}

// glTF's layer textures at a hit, applied to `out`'s dielectric f0 and f90, coat,
// transmission, thickness, sheen, anisotropy and film by the tracers' one text
// (core/layer_texels.h, the GPU's rt/material_at.glsl too).
void RtMaterials::applyLayerTextures(int material, const HitUv& uv, float footprint, HitMaterial& out) const {
  const auto& t = extras_[size_t(material)].layerTextures;
  const MaterialLayers& layers = materials_[size_t(material)].layers;
  glm::vec4 texel[kTextureSlots - kFirstLayerSlot] = {};
  bool present[kTextureSlots - kFirstLayerSlot] = {};
  for (size_t k = 0; k < t.size(); ++k) {
    // The coat's normal map (slot 6) is not read: the tracers read no normal maps.
    present[k] = k + kFirstLayerSlot != size_t(TextureSlot::ClearcoatNormal) && texelAt(textures_, t[k], uv, footprint, texel[k]);
  }
  brdf::LayerValues v;
  v.specularColor = layers.specularColor;
  v.specularWeight = layers.specular;
  v.clearcoat = out.clearcoat;
  v.clearcoatRoughness = out.clearcoatRoughness;
  v.transmission = out.transmission;
  v.thickness = out.thickness;
  v.sheenColor = out.sheenColor;
  v.sheenRoughness = out.sheenRoughness;
  v.anisotropyDirection = out.anisotropyDirection;
  v.anisotropy = out.anisotropy;
  v.iridescence = out.iridescence;
  v.iridescenceThickness = out.iridescenceThickness;
  v = brdf::withLayerTexels(v, texel, present,
                            glm::vec2(layers.iridescenceThicknessMin, layers.iridescenceThicknessMax));
  if (present[0] || present[1]) {
    out.dielectricF0 = brdf::layerF0(layers.reflectance(), v.specularColor, v.specularWeight);
    out.dielectricF90 = v.specularWeight;
  }
  out.clearcoat = v.clearcoat;
  out.clearcoatRoughness = v.clearcoatRoughness;
  out.transmission = v.transmission;
  out.thickness = v.thickness;
  out.sheenColor = v.sheenColor;
  out.sheenRoughness = v.sheenRoughness;
  out.anisotropyDirection = v.anisotropyDirection;
  out.anisotropy = v.anisotropy;
  out.iridescence = v.iridescence;
  out.iridescenceThickness = v.iridescenceThickness;
}

Status RtMaterials::setEmissiveTexture(int material, RtTexture texture) {
  return attachTexture(material, &MaterialExtras::emissiveTexture, std::move(texture));
}

float RtMaterials::opacityAt(int material, const HitUv& uv, float footprint) const {
  const MaterialExtras& e = extras_[size_t(material)];
  if (e.alphaMode == AlphaMode::Opaque) return 1.0f;
  const float alpha =
      e.alpha * uv.color.a * (e.texture >= 0 ? textures_[size_t(e.texture)].sampleRgba(uv, footprint).a : 1.0f);
  // MASK as scene.frag's discard: below the cutoff the surface is not there at all.
  if (e.alphaMode == AlphaMode::Mask) return alpha >= e.alphaCutoff ? 1.0f : 0.0f;
  return std::clamp(alpha, 0.0f, 1.0f);
}

Status RtMaterials::setTerrainMaterial(int material, RtTerrainMaterial layers) {
  if (auto s = checkMaterial(material); !s) return s.error();
  extras_[size_t(material)].terrain = int(terrains_.size());
  terrains_.push_back(std::move(layers));
  return Ok{};
}

HitMaterial RtMaterials::baseMaterial(int material) const {
  const MaterialDesc& m = materials_[size_t(material)];
  HitMaterial out{m.color, m.ambient, m.diffuse, m.specular, m.shininess, m.reflection,
                  m.metallic, m.roughness, m.emission, extras_[size_t(material)].unlit,
                  extras_[size_t(material)].dielectricF0, m.layers.dielectricF90(), m.layers.clearcoat,
                  m.layers.clearcoatRoughness, m.layers.transmission, m.layers.ior, m.layers.thickness,
                  m.layers.attenuationDistance, m.layers.attenuationColor, m.layers.sheenColor,
                  m.layers.sheenRoughness, m.layers.anisotropy, m.layers.anisotropyRotation};
  out.iridescence = m.layers.iridescence;
  out.iridescenceIor = m.layers.iridescenceIor;
  out.iridescenceThickness = m.layers.iridescenceThicknessMax;
  return out;
}

HitMaterial RtMaterials::materialAt(int material, const HitUv& uv, float footprint, double y, const glm::vec3& ns,
                                const glm::vec3& dpdu, const glm::vec3& dpdv) const {
  HitMaterial out = baseMaterial(material);
  const brdf::BaseValues base = baseAt(material, uv, footprint);
  out.albedo = base.albedo;
  out.metallic = base.metallic;
  out.roughness = base.roughness;
  out.emission = base.emission;
  if (extras_[size_t(material)].hasLayerTextures) applyLayerTextures(material, uv, footprint, out);
  if (out.anisotropy > 0.0f) {
    // The stretch in world space (core/layer_texels.h, the GPU's text too).
    const glm::vec4 a =
        brdf::orientedAnisotropy(out.anisotropyDirection, out.anisotropyRotation, out.anisotropy, ns, dpdu, dpdv);
    out.anisotropyT = glm::vec3(a);
    out.anisotropy = a.w;
  }
  if (const int terrain = extras_[size_t(material)].terrain; terrain >= 0) {
    const TerrainLayerSample layers = terrains_[size_t(terrain)].sample(uv.uv0, footprint, y, ns.y);
    out.albedo *= layers.albedo;
    out.roughness = layers.roughness;
    out.specular = layers.specular;
  }
  return out;
}

}  // namespace engine::rt
