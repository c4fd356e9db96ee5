#pragma once
// The path tracer's scattering at one hit: the material models of core/brdf.h (the
// rasterizer's own text) evaluated as BRDFs, with a sampling strategy for each lobe.
//
// CLASSIC, made physical: the course's diffuse and highlight divided by pi N.L (what
// its shadeLight multiplies a light by) are the BRDF, drawn with cosine-weighted
// directions; `reflection` is a perfect mirror of that weight, untinted, as in the
// Whitted tracer. Its `ambient` has no place here: indirect light replaces it.
// METALLIC-ROUGHNESS: brdf.glsl's Lambert + GGX (layeredBrdf, with glTF's ior,
// specular and clear coat), drawn by a mix of cosine-weighted directions and GGX
// visible normals of the base and of the coat, the mix following the lobes' Fresnel
// weights; an anisotropic base (KHR_materials_anisotropy) draws its visible normals
// from the stretched GGX in a frame whose x follows the stretch. A sheen (KHR_materials_sheen) over the base has a lobe of uniform
// directions in the mix: its lobe leans to the horizon, where cosine-weighted
// directions are rare (measured: 0.3 to 0.8 times their estimate's standard
// deviation, the least at low roughness and grazing views). The coat's normal is the shading normal: the tracers read no normal maps.
// KHR_materials_transmission adds a lobe through the surface, the dielectric's
// transmitted share (brdf.glsl's transmittedShare: what its Fresnel does not
// reflect, tinted by the base colour): GGX visible normals refract the ray by the
// ior into a volume (KHR_materials_volume; total internal reflection keeps it
// inside), or turn the facet's mirror direction through a thin wall. No light
// sample can be weighed against it (shadow rays stop at the surface), so it is
// drawn alone and counts what it finds in full, as a mirror does.
#include <optional>

#include <glm/glm.hpp>

#include "raytrace/rt_scene.h"
#include "raytrace/sampling.h"

namespace engine::rt {

struct BsdfSample {
  glm::vec3 wi{0.0f};      // world, unit
  glm::vec3 weight{0.0f};  // f * |cos| / pdf: what the path's throughput is multiplied by
  float pdf = 0.0f;        // of the lobe mixture; 0 for the mirror's delta
  bool delta = false;      // a mirror direction: no light sample can find it
  bool transmitted = false;  // through the surface (KHR_materials_transmission)
};

class Bsdf {
 public:
  // n: the unit shading normal on the viewer's side; wo: unit, toward the viewer.
  // `entering`: the viewer is outside the surface (its front face), which says which
  // way a volume's ior bends.
  static Bsdf classic(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo);
  static Bsdf metallicRoughness(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo, bool entering = true);

  // The BRDF for the light's direction wi (world, unit), mirror excluded.
  glm::vec3 f(const glm::vec3& wi) const;
  // The density sample() draws wi with through its non-delta lobes (solid angle).
  float pdf(const glm::vec3& wi) const;
  // u: two uniform numbers for the direction, uLobe one for the choice of lobe.
  std::optional<BsdfSample> sample(glm::vec2 u, float uLobe) const;
  // Whether any lobe is not a delta: only those gain from light samples.
  bool hasDiffuseOrGlossy() const { return pMirror_ < 1.0f; }
  const glm::vec3& normal() const { return frame_.n; }

 private:
  enum class Model { Classic, MetallicRoughness };
  Bsdf(Model model, const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo);
  std::optional<BsdfSample> lambertSample(glm::vec2 u) const;
  std::optional<BsdfSample> reflectionSample(glm::vec2 u, float uLobe) const;
  std::optional<BsdfSample> transmissionSample(glm::vec2 u) const;

  Model model_;
  HitMaterial m_;
  Frame frame_;
  glm::vec3 wo_;        // world
  glm::vec3 woLocal_;   // in frame_
  float alpha_ = 1.0f;  // GGX, metallic-roughness only
  float pMirror_ = 0.0f;    // classic: the mirror's share of the samples
  float pSpecular_ = 0.0f;  // metallic-roughness: the GGX lobe's share of the base's samples
  float pCoat_ = 0.0f;      // metallic-roughness: the clear coat's share of all samples
  float alphaCoat_ = 1.0f;
  float pTransmit_ = 0.0f;  // the transmission lobe's share of all samples
  float alphaTransmit_ = 1.0f;
  bool entering_ = true;
  // The layers' terms at wo (sheen scaling, anisotropy, the film's Fresnel).
  ViewLayers view_;
  float pSheen_ = 0.0f;  // the sheen's share of the samples under the coat
  // KHR_materials_anisotropy: the base lobe's alphas along frame_.s (the stretch's
  // direction) and frame_.t.
  glm::vec2 alphas_{1.0f};
};

}  // namespace engine::rt
