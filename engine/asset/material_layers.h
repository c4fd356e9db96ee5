#pragma once
// glTF's dielectric layers over the metallic-roughness base: KHR_materials_ior,
// KHR_materials_specular and KHR_materials_clearcoat, and the light that passes
// through the dielectric, KHR_materials_transmission and KHR_materials_volume, and
// the fibres over it, KHR_materials_sheen, the stretch of its highlight,
// KHR_materials_anisotropy, and a thin film on it, KHR_materials_iridescence: their
// factors (the textures are MaterialData's slots past Occlusion). Every renderer
// evaluates them through layeredBrdf (shaders/common/brdf.glsl); a material whose
// layers are the defaults draws exactly as plain metallic-roughness.
#include <glm/glm.hpp>

namespace engine {

struct MaterialLayers {
  float ior = 1.5f;               // KHR_materials_ior
  float specular = 1.0f;          // KHR_materials_specular: specularFactor
  glm::vec3 specularColor{1.0f};  // specularColorFactor, linear
  float clearcoat = 0.0f;         // KHR_materials_clearcoat: clearcoatFactor
  float clearcoatRoughness = 0.0f;
  float clearcoatNormalScale = 1.0f;  // clearcoatNormalTexture's scale
  // KHR_materials_transmission: the share of the dielectric's diffuse lobe that is
  // transmitted through the surface instead (metals transmit nothing).
  float transmission = 0.0f;
  // KHR_materials_volume: the thickness of the volume under the surface, in the
  // mesh's units (0: thin-walled, the light leaves unbent), and Beer-Lambert's
  // absorption: white light turns attenuationColor after attenuationDistance
  // (0 = infinite, nothing absorbed).
  float thickness = 0.0f;
  float attenuationDistance = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  // KHR_materials_sheen: the colour (linear) and roughness of a layer of fibres over
  // the base; a black sheen is none.
  glm::vec3 sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  // KHR_materials_anisotropy: how far the base's GGX lobe stretches (0 none, 1 most)
  // and the direction's turn from the tangent toward the bitangent, in radians.
  float anisotropy = 0.0f;
  float anisotropyRotation = 0.0f;
  // KHR_materials_iridescence: the thin film's share, its index, and its thickness in
  // nanometres (the maximum without a thickness texture; the texture's G goes from
  // the minimum to the maximum).
  float iridescence = 0.0f;
  float iridescenceIor = 1.3f;
  float iridescenceThicknessMin = 100.0f;
  float iridescenceThicknessMax = 400.0f;

  bool isDefault() const {
    return ior == 1.5f && specular == 1.0f && specularColor == glm::vec3(1.0f) && clearcoat == 0.0f &&
           transmission == 0.0f && !sheen() && anisotropy == 0.0f && iridescence == 0.0f;
  }
  bool transmissive() const { return transmission > 0.0f; }
  bool sheen() const { return sheenColor != glm::vec3(0.0f); }
  // The dielectric's reflectance at normal incidence: ((ior - 1) / (ior + 1))^2 times
  // the specular colour (each channel at most 1), times the specular weight. Worked
  // in double, so that ior 1.5 gives the very float 0.04f of metallicF0.
  glm::vec3 dielectricF0() const { return dielectricF0(specularColor, specular); }
  // The same with the colour and weight at a point (their textures applied).
  glm::vec3 dielectricF0(glm::vec3 color, float weight) const {
    const glm::dvec3 f0 = glm::min(glm::dvec3(reflectance()) * glm::dvec3(color), glm::dvec3(1.0)) * double(weight);
    return glm::vec3(f0);
  }
  // ((ior - 1) / (ior + 1))^2 alone, for the shaders that tint it per pixel.
  float iorF0() const { return float(reflectance()); }
  // ... and at grazing angles: the specular weight.
  float dielectricF90() const { return specular; }
  // ((ior - 1) / (ior + 1))^2 in double, which dielectricF0 tints (the GPU tracer
  // tints it per hit by the specular textures as dielectricF0 does).
  double reflectance() const {
    const double r = (double(ior) - 1.0) / (double(ior) + 1.0);
    return r * r;
  }
};

}  // namespace engine
