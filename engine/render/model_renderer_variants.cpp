// Shader variants: what each one is called and #defines, the cache of their
// programs, and the variant a primitive needs.
#include <string>
#include <vector>

#include "render/model_renderer_impl.h"

namespace engine {

std::string ShaderVariant::describe() const {
  std::string name = influences == 0 ? "static"
                                     : std::string(mode == SkinMode::DualQuat ? "dqs" : "lbs") +
                                           std::to_string(influences);
  if (morph) name += "+morph";
  if (textured) name += "+textured";
  if (normalMap) name += "+normalmap";
  if (metallicRoughnessTexture) name += "+mr";
  if (emissiveTexture) name += "+emissive";
  if (occlusion) name += "+occlusion";
  if (alphaMask) name += "+mask";
  if (uvTransform) name += "+uvtransform";
  if (vertexColor) name += "+vertexcolor";
  if (unlit) name += "+unlit";
  if (layers) name += "+layers";
  if (layerTextures) name += "+layertextures";
  if (transmission) name += "+transmission";
  if (clearcoatNormal) name += "+coatnormal";
  if (sheen) name += "+sheen";
  if (anisotropy) name += "+anisotropy";
  if (iridescence) name += "+iridescence";
  if (matte) name += "+matte";
  if (nearSunOnly) name += "+nearsun";
  if (oneSided) name += "+onesided";
  if (depthOnly) name += "+depth";
  if (surface == Surface::Out) name += "+surface";
  if (surface == Surface::In) name += "+fromsurface";
  return name;
}

bool ShaderVariant::deferrable() const {
  return !depthOnly && !normalMap && !metallicRoughnessTexture && !emissiveTexture && !occlusion && !alphaMask &&
         !uvTransform && !unlit && !vertexColor && !layers && !layerTextures && !transmission && !clearcoatNormal &&
         !sheen && !anisotropy && !iridescence && surface == Surface::None;
}

ShaderVariant ShaderVariant::shadingFromSurface() const {
  ShaderVariant v = *this;
  v.influences = 0;
  v.mode = SkinMode::Linear;
  v.morph = false;
  v.oneSided = false;
  v.nearSunOnly = false;
  v.surface = Surface::In;
  return v;
}

Result<const gl::Program*> ShaderVariants::get(const ShaderVariant& asked,
                                              const std::vector<std::string>& feedback) {
  ShaderVariant variant = asked;
  // A surface pass lights nothing: neither flag changes what it writes.
  const bool lights = !asked.depthOnly && asked.surface != ShaderVariant::Surface::Out;
  variant.matte = asked.matte && classic_ && lights;
  variant.nearSunOnly = asked.nearSunOnly && farSun_ && lights;
  variant.oneSided = asked.oneSided && !asked.depthOnly;
  // Programs with transform feedback (one-off captures) live in their own cache:
  // a pointer handed out for the plain variant stays valid and keeps its program.
  if (feedback.empty()) {
    if (auto it = programs_.find(variant); it != programs_.end()) return &it->second;
  } else if (auto it = feedbackPrograms_.find({variant, feedback}); it != feedbackPrograms_.end()) {
    return &it->second;
  }
  auto program = build(variant, feedback);
  if (!program) return program.error();
  gl::Program& stored = feedback.empty() ? programs_[variant] : feedbackPrograms_[{variant, feedback}];
  stored = std::move(program).value();
  return &stored;
}

Result<gl::Program> ShaderVariants::build(const ShaderVariant& variant, const std::vector<std::string>& feedback) const {
  std::vector<std::string> defines = defines_;
  if (variant.nearSunOnly) std::erase(defines, std::string(kFarSunDefine));
  if (variant.textured) defines.push_back("TEXTURED 1");
  if (variant.depthOnly) defines.push_back("DEPTH_ONLY 1");
  if (variant.normalMap) defines.push_back("NORMAL_MAP 1");
  if (variant.metallicRoughnessTexture) defines.push_back("MR_TEXTURE 1");
  if (variant.emissiveTexture) defines.push_back("EMISSIVE_TEXTURE 1");
  if (variant.occlusion) defines.push_back("OCCLUSION 1");
  if (variant.alphaMask) defines.push_back("ALPHA_MASK 1");
  if (variant.morph) defines.push_back("MORPH 1");
  if (variant.uvTransform) defines.push_back("UV_TRANSFORM 1");
  if (variant.vertexColor) defines.push_back("VERTEX_COLOR 1");
  if (variant.unlit) defines.push_back("UNLIT 1");
  if (variant.layers) defines.push_back("MATERIAL_LAYERS 1");
  if (variant.layerTextures) defines.push_back("LAYER_TEXTURES 1");
  if (variant.transmission) defines.push_back("TRANSMISSION 1");
  if (variant.clearcoatNormal) defines.push_back("CLEARCOAT_NORMAL 1");
  if (variant.sheen) defines.push_back("SHEEN 1");
  if (variant.anisotropy) defines.push_back("ANISOTROPY 1");
  if (variant.iridescence) defines.push_back("IRIDESCENCE 1");
  if (variant.matte) defines.push_back("CLASSIC_MATTE 1");
  if (variant.oneSided) defines.push_back("ONE_SIDED 1");
  if (variant.surface == ShaderVariant::Surface::Out) defines.push_back("SURFACE_OUT 1");
  if (variant.surface == ShaderVariant::Surface::In) defines.push_back("SURFACE_IN 1");
  if (variant.influences > 0) {
    defines.push_back("SKINNED 1");
    defines.push_back("INFLUENCES " + std::to_string(variant.influences));
    if (variant.mode == SkinMode::DualQuat) defines.push_back("DUAL_QUAT 1");
  }
  const std::string fragment = variant.depthOnly ? "depth.frag" : "scene.frag";
  const std::string vertex = variant.surface == ShaderVariant::Surface::In ? "sky.vert" : "scene.vert";
  return gl::Program::build(shaderDir_, {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, defines,
                            feedback);
}

std::vector<ShaderVariant> ShaderVariants::built() const {
  std::vector<ShaderVariant> out;
  for (const auto& entry : programs_) out.push_back(entry.first);
  return out;
}

ShaderVariant primitiveVariant(const ModelData& model, const NodeData& node, const PrimitiveData& prim,
                               SkinMode mode, bool depthOnly, bool cached) {
  ShaderVariant v;
  v.influences = skinnedBy(node, prim.influences, mode) && !cached ? prim.influences : 0;
  // The blend only matters to skinning code: every static variant is one program,
  // whichever mode (or cache) the model draws with.
  v.mode = v.influences > 0 ? mode : SkinMode::Linear;
  v.morph = prim.morphTargets > 0 && !cached;
  v.depthOnly = depthOnly;
  const MaterialData* m = materialOf(model, prim.material);
  const bool colored = !prim.colors.empty();  // COLOR_0 multiplies the base colour
  v.vertexColor = colored && !depthOnly;
  v.matte = classicSpecularOf(m ? m->roughnessFactor : 1.0f) <= 0.0f;
  v.oneSided = !m || !m->doubleSided;  // glTF's default material is one-sided
  if (!m) return v;
  v.alphaMask = m->alphaMode == AlphaMode::Mask;
  // A shadow pass needs the material only to cut out MASK holes.
  if (depthOnly) {
    v.textured = v.alphaMask && m->baseColorImage >= 0;
    v.vertexColor = colored && v.alphaMask;
  } else if (m->unlit) {
    // Nothing but the base colour is read: no variant for the other slots.
    v.textured = m->baseColorImage >= 0;
    v.unlit = true;
  } else {
    v.textured = m->baseColorImage >= 0;
    v.normalMap = m->normalImage >= 0 && !prim.tangents.empty();
    v.metallicRoughnessTexture = m->metallicRoughnessImage >= 0;
    v.emissiveTexture = m->emissiveImage >= 0;
    v.occlusion = m->occlusionImage >= 0;
    v.layers = m->layered();
    v.layerTextures = m->hasLayerTextures();
    v.transmission = m->layers.transmissive();
    v.clearcoatNormal = m->layers.clearcoat > 0.0f && m->image(TextureSlot::ClearcoatNormal) >= 0 && !prim.tangents.empty();
    v.sheen = m->layers.sheen();
    v.anisotropy = m->layers.anisotropy > 0.0f && !prim.tangents.empty();
    v.iridescence = m->layers.iridescence > 0.0f;
  }
  const auto sampled = sampledSlots(v, presentSlots(*m));
  for (int i = 0; i < kTextureSlots; ++i) v.uvTransform |= sampled[size_t(i)] && m->textures[size_t(i)].transformsUv();
  return v;
}

}  // namespace engine
