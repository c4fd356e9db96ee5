// Materials: the core PBR slots and factors, the KHR_materials_* extensions, and
// each texture slot's uv set, KHR_texture_transform and sampler.
#include <cmath>
#include <cstdio>

#include "asset/gltf_loader_impl.h"
#include "asset/texture_transform.h"

namespace engine::gltf_loader {
namespace {

// KHR_materials_emissive_strength: a multiplier of emissiveFactor (1 without it),
// so that emission can pass 1 in an HDR target.
Result<float> emissiveStrength(const tinygltf::Material& material, const std::string& name) {
  auto ext = material.extensions.find("KHR_materials_emissive_strength");
  if (ext == material.extensions.end() || !ext->second.Has("emissiveStrength")) return 1.0f;
  const tinygltf::Value& value = ext->second.Get("emissiveStrength");
  const double strength = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
  if (!(strength >= 0.0) || !std::isfinite(strength) || strength > 1e30) {
    return makeError(name + ": KHR_materials_emissive_strength: emissiveStrength must be a finite number >= 0");
  }
  return static_cast<float>(strength);
}

// One number of a material extension: `fallback` when absent, an error naming the
// material, the extension and the key when it is not a number inside [lo, hi].
Result<float> extensionNumber(const tinygltf::Value& ext, const char* key, float fallback, double lo, double hi,
                              const std::string& where) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& value = ext.Get(key);
  const double v = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
  if (!(v >= lo && v <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
    return makeError(where + ": " + key + " must be a number in " + range);
  }
  return static_cast<float>(v);
}

// One colour of a material extension: `fallback` when absent, an error naming the
// material, the extension and the key unless it is three numbers in [0, most].
Result<glm::vec3> extensionColor(const tinygltf::Value& ext, const char* key, float most, const std::string& where,
                                 const char* expected, glm::vec3 fallback = glm::vec3(1.0f)) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& c = ext.Get(key);
  const bool ok = c.IsArray() && c.ArrayLen() == 3 && c.Get(0).IsNumber() && c.Get(1).IsNumber() && c.Get(2).IsNumber();
  const glm::vec3 color = ok ? glm::vec3(c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble())
                             : glm::vec3(-1.0f);
  if (!(glm::all(glm::greaterThanEqual(color, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(color, glm::vec3(most)))))
    return makeError(where + ": " + key + " must be " + expected);
  return color;
}

// KHR_materials_volume: thickness and Beer-Lambert's attenuation.
Status readVolume(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_volume";
  auto thickness = extensionNumber(ext, "thicknessFactor", 0.0f, 0.0, 1e30, where);
  if (!thickness) return thickness.error();
  // Absent means infinite (nothing absorbed), which MaterialLayers writes as 0.
  auto distance = extensionNumber(ext, "attenuationDistance", 0.0f, 0.0, 1e30, where);
  if (!distance) return distance.error();
  if (ext.Has("attenuationDistance") && !(*distance > 0.0f)) return makeError(where + ": attenuationDistance must be > 0");
  layers.thickness = *thickness;
  layers.attenuationDistance = *distance;
  auto color = extensionColor(ext, "attenuationColor", 1.0f, where, "three numbers in [0, 1]");
  if (!color) return color.error();
  layers.attenuationColor = *color;
  return Ok{};
}

// KHR_materials_sheen: the fibres' colour (black, none, when absent) and roughness.
Status readSheen(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_sheen";
  auto color = extensionColor(ext, "sheenColorFactor", 1.0f, where, "three numbers in [0, 1]", glm::vec3(0.0f));
  if (!color) return color.error();
  auto roughness = extensionNumber(ext, "sheenRoughnessFactor", 0.0f, 0.0, 1.0, where);
  if (!roughness) return roughness.error();
  layers.sheenColor = *color;
  layers.sheenRoughness = *roughness;
  return Ok{};
}

// KHR_materials_anisotropy: the stretch's strength and its direction's turn.
Status readAnisotropy(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_anisotropy";
  auto strength = extensionNumber(ext, "anisotropyStrength", 0.0f, 0.0, 1.0, where);
  if (!strength) return strength.error();
  auto rotation = extensionNumber(ext, "anisotropyRotation", 0.0f, -1e6, 1e6, where);
  if (!rotation) return rotation.error();
  layers.anisotropy = *strength;
  layers.anisotropyRotation = *rotation;
  return Ok{};
}

// KHR_materials_iridescence: the film's share, index and thickness range (nm).
Status readIridescence(const tinygltf::Value& ext, const std::string& name, MaterialLayers& layers) {
  const std::string where = name + ": KHR_materials_iridescence";
  auto factor = extensionNumber(ext, "iridescenceFactor", 0.0f, 0.0, 1.0, where);
  if (!factor) return factor.error();
  auto ior = extensionNumber(ext, "iridescenceIor", 1.3f, 1.0, 1e6, where);
  if (!ior) return ior.error();
  auto thinnest = extensionNumber(ext, "iridescenceThicknessMinimum", 100.0f, 0.0, 1e6, where);
  if (!thinnest) return thinnest.error();
  auto thickest = extensionNumber(ext, "iridescenceThicknessMaximum", 400.0f, 0.0, 1e6, where);
  if (!thickest) return thickest.error();
  layers.iridescence = *factor;
  layers.iridescenceIor = *ior;
  layers.iridescenceThicknessMin = *thinnest;
  layers.iridescenceThicknessMax = *thickest;
  return Ok{};
}

// KHR_materials_ior, _specular, _clearcoat, _transmission, _volume, _sheen,
// _anisotropy and _iridescence.
Result<MaterialLayers> materialLayers(const tinygltf::Material& material, const std::string& name) {
  MaterialLayers layers;
  auto has = [&](const char* ext) { return material.extensions.find(ext) != material.extensions.end(); };
  if (has("KHR_materials_ior")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_ior");
    // glTF allows 0 besides [1, inf): it reads as a perfect mirror (f0 = 1).
    auto ior = extensionNumber(ext, "ior", 1.5f, 0.0, 1e6, name + ": KHR_materials_ior");
    if (!ior) return ior.error();
    if (*ior > 0.0f && *ior < 1.0f) return makeError(name + ": KHR_materials_ior: ior must be 0 or at least 1");
    layers.ior = *ior;
  }
  if (has("KHR_materials_specular")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_specular");
    const std::string where = name + ": KHR_materials_specular";
    auto weight = extensionNumber(ext, "specularFactor", 1.0f, 0.0, 1.0, where);
    if (!weight) return weight.error();
    layers.specular = *weight;
    auto color = extensionColor(ext, "specularColorFactor", 1e6f, where, "three numbers >= 0");
    if (!color) return color.error();
    layers.specularColor = *color;
  }
  if (has("KHR_materials_clearcoat")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_clearcoat");
    const std::string where = name + ": KHR_materials_clearcoat";
    auto coat = extensionNumber(ext, "clearcoatFactor", 0.0f, 0.0, 1.0, where);
    if (!coat) return coat.error();
    auto roughness = extensionNumber(ext, "clearcoatRoughnessFactor", 0.0f, 0.0, 1.0, where);
    if (!roughness) return roughness.error();
    layers.clearcoat = *coat;
    layers.clearcoatRoughness = *roughness;
  }
  if (has("KHR_materials_transmission")) {
    auto transmission = extensionNumber(material.extensions.at("KHR_materials_transmission"), "transmissionFactor",
                                        0.0f, 0.0, 1.0, name + ": KHR_materials_transmission");
    if (!transmission) return transmission.error();
    layers.transmission = *transmission;
  }
  if (has("KHR_materials_volume")) {
    if (auto status = readVolume(material.extensions.at("KHR_materials_volume"), name, layers); !status) return status.error();
  }
  if (has("KHR_materials_sheen")) {
    if (auto status = readSheen(material.extensions.at("KHR_materials_sheen"), name, layers); !status) return status.error();
  }
  if (has("KHR_materials_anisotropy")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_anisotropy");
    if (auto status = readAnisotropy(ext, name, layers); !status) return status.error();
  }
  if (has("KHR_materials_iridescence")) {
    const tinygltf::Value& ext = material.extensions.at("KHR_materials_iridescence");
    if (auto status = readIridescence(ext, name, layers); !status) return status.error();
  }
  return layers;
}

}  // namespace

// The image behind a material's texture slot, or -1, and how the slot samples
// it (`slot`: uv set, KHR_texture_transform, sampler). A texture index or source
// out of range is a warning naming the material and the slot, and the slot is
// left empty; a uv set other than 0 and 1, a malformed transform or sampler a
// warning, and the default is used in its place.
template <typename Info>
int Converter::textureImage(const Info& info, const std::string& material, const char* slotName, TextureSlotData& slot) {
  if (info.index < 0) return -1;
  const std::string where = material + ": " + slotName + " " + str(info.index);
  if (!validIndex(info.index, gltf_.textures.size())) {
    warn(where + " does not exist; drawn without it");
    return -1;
  }
  const tinygltf::Texture& texture = gltf_.textures[static_cast<std::size_t>(info.index)];
  const int source = texture.source;
  if (!validIndex(source, out_.images.size())) {
    warn(where + ": image " + str(source) + " does not exist; drawn without it");
    return -1;
  }
  int texCoord = info.texCoord;
  if (auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end())
    readTextureTransform(ext->second, where + ": KHR_texture_transform", slot, texCoord);
  if (texCoord != 0 && texCoord != 1) {
    warn(where + ": TEXCOORD_" + str(texCoord) + " is not supported (TEXCOORD_0 and TEXCOORD_1 are); TEXCOORD_0 is used");
    texCoord = 0;
  }
  slot.texCoord = texCoord;
  if (texture.sampler >= 0) slot.sampler = readSampler(texture.sampler, where);
  return source;
}

// A textureInfo inside a material extension, which tinygltf leaves as JSON.
struct Converter::ExtensionTextureInfo {
  int index = -1;
  int texCoord = 0;
  tinygltf::ExtensionMap extensions;
};
Converter::ExtensionTextureInfo Converter::extensionTextureInfo(const tinygltf::Value& v) {
  ExtensionTextureInfo info;
  if (!v.IsObject()) return info;
  if (v.Has("index") && v.Get("index").IsNumber()) info.index = v.Get("index").GetNumberAsInt();
  if (v.Has("texCoord") && v.Get("texCoord").IsNumber()) info.texCoord = v.Get("texCoord").GetNumberAsInt();
  if (v.Has("extensions") && v.Get("extensions").IsObject()) {
    const tinygltf::Value& ext = v.Get("extensions");
    for (const std::string& key : ext.Keys()) info.extensions[key] = ext.Get(key);
  }
  return info;
}

// The textures of KHR_materials_specular, _clearcoat (its normal map too),
// _transmission, _volume, _sheen, _anisotropy and _iridescence, each with its uv set, transform and sampler as the
// core slots have them.
void Converter::readLayerTextures(const tinygltf::Material& src, const std::string& name, MaterialData& m) {
  struct Key {
    const char* extension;
    const char* key;
    TextureSlot slot;
  };
  static const Key kKeys[] = {{"KHR_materials_specular", "specularTexture", TextureSlot::Specular},
                              {"KHR_materials_specular", "specularColorTexture", TextureSlot::SpecularColor},
                              {"KHR_materials_clearcoat", "clearcoatTexture", TextureSlot::Clearcoat},
                              {"KHR_materials_clearcoat", "clearcoatRoughnessTexture", TextureSlot::ClearcoatRoughness},
                              {"KHR_materials_transmission", "transmissionTexture", TextureSlot::Transmission},
                              {"KHR_materials_volume", "thicknessTexture", TextureSlot::Thickness},
                              {"KHR_materials_clearcoat", "clearcoatNormalTexture", TextureSlot::ClearcoatNormal},
                              {"KHR_materials_sheen", "sheenColorTexture", TextureSlot::SheenColor},
                              {"KHR_materials_sheen", "sheenRoughnessTexture", TextureSlot::SheenRoughness},
                              {"KHR_materials_anisotropy", "anisotropyTexture", TextureSlot::Anisotropy},
                              {"KHR_materials_iridescence", "iridescenceTexture", TextureSlot::Iridescence},
                              {"KHR_materials_iridescence", "iridescenceThicknessTexture",
                               TextureSlot::IridescenceThickness}};
  for (const Key& k : kKeys) {
    auto ext = src.extensions.find(k.extension);
    if (ext == src.extensions.end() || !ext->second.Has(k.key)) continue;
    const ExtensionTextureInfo info = extensionTextureInfo(ext->second.Get(k.key));
    if (info.index < 0) {
      warn(name + ": " + k.extension + ": " + k.key + " has no texture index; drawn without it");
      continue;
    }
    const std::string slotName = std::string(k.extension) + ": " + k.key;
    m.layerImages[std::size_t(k.slot) - kFirstLayerSlot] = textureImage(info, name, slotName.c_str(), m.texture(k.slot));
    if (k.slot == TextureSlot::ClearcoatNormal) m.layers.clearcoatNormalScale = normalScale(ext->second.Get(k.key));
  }
}

// A normal map's textureInfo "scale" (1 when absent or not a finite number).
float Converter::normalScale(const tinygltf::Value& info) {
  if (!info.Has("scale") || !info.Get("scale").IsNumber()) return 1.0f;
  const double scale = info.Get("scale").GetNumberAsDouble();
  return std::isfinite(scale) && std::abs(scale) < 1e6 ? float(scale) : 1.0f;
}

// KHR_texture_transform on one textureInfo: offset, rotation, scale (each
// defaulted when absent or malformed, with a warning for the latter) and the
// texCoord that overrides the textureInfo's.
void Converter::readTextureTransform(const tinygltf::Value& ext, const std::string& where, TextureSlotData& slot,
                                     int& texCoord) {
  auto number = [&](const tinygltf::Value& v, double& out) {
    if (!v.IsNumber()) return false;
    out = v.GetNumberAsDouble();
    return std::isfinite(out) && std::abs(out) < 1e30;
  };
  auto vec2 = [&](const char* key, glm::vec2 fallback) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    double x = 0.0, y = 0.0;
    if (!v.IsArray() || v.ArrayLen() != 2 || !number(v.Get(0), x) || !number(v.Get(1), y)) {
      warn(where + ": " + key + " must be 2 finite numbers; [" + (fallback.x == 0.0f ? "0, 0" : "1, 1") +
           "] is used");
      return fallback;
    }
    return glm::vec2(float(x), float(y));
  };
  const glm::vec2 offset = vec2("offset", glm::vec2(0.0f));
  const glm::vec2 scale = vec2("scale", glm::vec2(1.0f));
  double rotation = 0.0;
  if (ext.Has("rotation") && !number(ext.Get("rotation"), rotation)) {
    warn(where + ": rotation must be a finite number; 0 is used");
    rotation = 0.0;
  }
  if (ext.Has("texCoord")) {
    const tinygltf::Value& v = ext.Get("texCoord");
    if (v.IsInt() && v.GetNumberAsInt() >= 0) texCoord = v.GetNumberAsInt();
    else warn(where + ": texCoord must be an integer >= 0; the textureInfo's TEXCOORD_" + str(texCoord) + " is used");
  }
  slot.uvTransform = textureTransformMatrix(offset, float(rotation), scale);
}

// A glTF sampler's wrap modes and filters; an unknown value (or a sampler that
// does not exist) is a warning and glTF's default in its place.
SamplerData Converter::readSampler(int index, const std::string& where) {
  SamplerData out;
  if (!validIndex(index, gltf_.samplers.size())) {
    warn(where + ": sampler " + str(index) + " does not exist; repeat and trilinear are used");
    return out;
  }
  const tinygltf::Sampler& s = gltf_.samplers[static_cast<std::size_t>(index)];
  const std::string name = where + ": sampler " + str(index);
  auto wrap = [&](int value, const char* key) {
    if (value == 10497 || value == 33071 || value == 33648) return static_cast<TextureWrap>(value);
    warn(name + ": " + key + " " + str(value) + " is not a wrap mode; REPEAT is used");
    return TextureWrap::Repeat;
  };
  out.wrapS = wrap(s.wrapS, "wrapS");
  out.wrapT = wrap(s.wrapT, "wrapT");
  if (s.magFilter == 9728 || s.magFilter == 9729) out.magFilter = static_cast<TextureFilter>(s.magFilter);
  else if (s.magFilter != -1) warn(name + ": magFilter " + str(s.magFilter) + " is not NEAREST or LINEAR; LINEAR is used");
  if (s.minFilter == 9728 || s.minFilter == 9729 || (s.minFilter >= 9984 && s.minFilter <= 9987))
    out.minFilter = static_cast<TextureFilter>(s.minFilter);
  else if (s.minFilter != -1)
    warn(name + ": minFilter " + str(s.minFilter) + " is not a glTF filter; LINEAR_MIPMAP_LINEAR is used");
  return out;
}

std::string Converter::imageName(int image) const {
  const ImageData& data = out_.images[static_cast<std::size_t>(image)];
  return "image " + str(image) + (data.uri.empty() ? "" : " (" + data.uri + ")");
}

Status Converter::convertMaterials() {
  for (std::size_t i = 0; i < gltf_.materials.size(); ++i) {
    const tinygltf::Material& src = gltf_.materials[i];
    const std::string name = labelled("material", i, src.name);
    MaterialData m;
    m.name = src.name;
    const auto& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
      m.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                                    pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    m.baseColorImage = textureImage(pbr.baseColorTexture, name, "baseColorTexture", m.texture(TextureSlot::BaseColor));
    m.metallicFactor = static_cast<float>(pbr.metallicFactor);
    m.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
    m.metallicRoughnessImage = textureImage(pbr.metallicRoughnessTexture, name, "metallicRoughnessTexture", m.texture(TextureSlot::MetallicRoughness));
    m.normalImage = textureImage(src.normalTexture, name, "normalTexture", m.texture(TextureSlot::Normal));
    m.normalScale = static_cast<float>(src.normalTexture.scale);
    // A missing image becomes white (see convertImages), which is neutral for
    // every slot but the normal map, where it would tilt every normal: there the
    // fallback is the mesh's own normals.
    if (m.normalImage >= 0 && out_.images[static_cast<std::size_t>(m.normalImage)].missing) {
      warn(name + ": normalTexture " + imageName(m.normalImage) + " is missing; drawn with the mesh normals");
      m.normalImage = -1;
    }
    m.occlusionImage = textureImage(src.occlusionTexture, name, "occlusionTexture", m.texture(TextureSlot::Occlusion));
    m.occlusionStrength = static_cast<float>(src.occlusionTexture.strength);
    m.emissiveImage = textureImage(src.emissiveTexture, name, "emissiveTexture", m.texture(TextureSlot::Emissive));
    if (src.emissiveFactor.size() == 3)
      m.emissiveFactor = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
    auto strength = emissiveStrength(src, name);
    if (!strength) return error(strength.error().message);
    m.emissiveFactor *= *strength;
    m.doubleSided = src.doubleSided;
    m.unlit = src.extensions.count("KHR_materials_unlit") > 0;
    auto layers = materialLayers(src, name);
    if (!layers) return error(layers.error().message);
    m.layers = *layers;
    readLayerTextures(src, name, m);
    m.alphaMode = src.alphaMode == "BLEND" ? AlphaMode::Blend : src.alphaMode == "MASK" ? AlphaMode::Mask : AlphaMode::Opaque;
    m.alphaCutoff = static_cast<float>(src.alphaCutoff);
    const bool finite = std::isfinite(m.normalScale) && std::isfinite(m.occlusionStrength) &&
                        std::isfinite(m.alphaCutoff) && std::isfinite(m.metallicFactor) &&
                        std::isfinite(m.roughnessFactor) && std::isfinite(m.baseColorFactor.x + m.baseColorFactor.y +
                                                                          m.baseColorFactor.z + m.baseColorFactor.w) &&
                        std::isfinite(m.emissiveFactor.x + m.emissiveFactor.y + m.emissiveFactor.z);
    if (!finite) return error(name + ": a factor is NaN or infinite");
    out_.materials.push_back(std::move(m));
  }
  return Ok{};
}

}  // namespace engine::gltf_loader
