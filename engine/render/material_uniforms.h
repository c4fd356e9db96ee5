#pragma once
// A material's uniforms (common/material.glsl, common/shading.glsl) from the scene
// layer's table (scene/materials.h), handed one by one to `set(name, value)`: the
// rasterizer's draws pass gl::Program::set, a test records them to hold them against
// the tracers' HitMaterial. GL-free, so that what a draw is given can be read
// without a context.
#include "scene/materials.h"

namespace engine {

// What every draw shades with, a scene shape's as a glTF primitive's: both shading
// models' weights (the classic model reads ambient .. reflection, PBR metallic and
// roughness) and the emission.
template <typename Set>
void forEachSurfaceUniform(const SceneMaterial& m, Set&& set) {
  const MaterialDesc& s = m.surface;
  set("u_baseColorFactor", m.baseColor());
  set("u_metallic", s.metallic);
  set("u_roughness", s.roughness);
  set("u_emissive", s.emission);
  set("u_ambient", s.ambient);
  set("u_diffuse", s.diffuse);
  set("u_specular", s.specular);
  set("u_shininess", s.shininess);
  set("u_reflection", s.reflection);
}

// glTF's layers (only where the layered BRDF is drawn: a plain material's variant
// reads none) and its maps' scales and MASK's cutoff.
template <typename Set>
void forEachGltfUniform(const SceneMaterial& m, Set&& set) {
  if (m.layered) {
    const MaterialLayers& l = m.surface.layers;
    set("u_iorF0", l.iorF0());
    set("u_specularWeight", l.specular);
    set("u_specularColor", l.specularColor);
    set("u_clearcoat", l.clearcoat);
    set("u_clearcoatRoughness", l.clearcoatRoughness);
    set("u_transmission", l.transmission);
    set("u_thickness", l.thickness);
    set("u_ior", l.ior);
    set("u_attenuationDistance", l.attenuationDistance);
    set("u_attenuationColor", l.attenuationColor);
    set("u_clearcoatNormalScale", l.clearcoatNormalScale);
    set("u_sheenColor", l.sheenColor);
    set("u_sheenRoughness", l.sheenRoughness);
    set("u_anisotropy", l.anisotropy);
    set("u_anisotropyRotation", l.anisotropyRotation);
    set("u_iridescence", l.iridescence);
    set("u_iridescenceIor", l.iridescenceIor);
    set("u_iridescenceThickness", glm::vec2(l.iridescenceThicknessMin, l.iridescenceThicknessMax));
  }
  set("u_normalScale", m.normalScale);
  set("u_occlusionStrength", m.occlusionStrength);
  set("u_alphaCutoff", m.alphaCutoff);
}

// Everything a glTF primitive's colour pass is given of its material.
template <typename Set>
void forEachMaterialUniform(const SceneMaterial& m, Set&& set) {
  forEachSurfaceUniform(m, set);
  forEachGltfUniform(m, set);
}

}  // namespace engine
