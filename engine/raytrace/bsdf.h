#pragma once
// The path tracer's scattering at one hit: shaders/common/bsdf.glsl, the GPU path
// tracer's text, compiled as C++ (core/bsdf.h), under the class its callers use. What the models and their lobes are is said there: the
// classic model made physical (Lambert, the course's highlight and a mirror) and
// metallic-roughness (Lambert + GGX with glTF's layers: ior and specular, clear coat,
// sheen, thin film, anisotropy, transmission through thin walls and into volumes).
#include <glm/glm.hpp>

#include "core/bsdf.h"
#include "raytrace/rt_materials.h"

namespace engine::rt {

// A drawn direction (the shared text's): `drawn` false where nothing was (the
// direction fell under the surface, or a zero pdf); else wi (world, unit), weight
// (f |cos| / pdf, what the path's throughput is multiplied by), pdf (of the lobe
// mixture; 0 for a delta), delta (a mirror or transmitted direction: no light sample
// can find it) and transmitted (through the surface, KHR_materials_transmission).
// The text's struct itself, not a copy in an optional: the copy, narrow stores read
// back by wide loads, stalled store forwarding on every bounce (7 % of the course
// room's path trace).
using BsdfSample = brdf::BsdfSample;

class Bsdf {
 public:
  // n: the unit shading normal on the viewer's side; wo: unit, toward the viewer.
  // `entering`: the viewer is outside the surface (its front face), which says which
  // way a volume's ior bends.
  static Bsdf classic(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo);
  static Bsdf metallicRoughness(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo, bool entering = true);

  // The BRDF for the light's direction wi (world, unit), mirror excluded.
  glm::vec3 f(const glm::vec3& wi) const { return brdf::bsdfF(b_, wi); }
  // The density sample() draws wi with through its non-delta lobes (solid angle).
  float pdf(const glm::vec3& wi) const { return brdf::bsdfPdf(b_, wi); }
  // u: two uniform numbers for the direction, uLobe one for the choice of lobe.
  BsdfSample sample(glm::vec2 u, float uLobe) const { return brdf::bsdfSampleOf(b_, u, uLobe); }
  // Whether any lobe is not a delta: only those gain from light samples.
  bool hasDiffuseOrGlossy() const { return b_.pMirror < 1.0f; }
  const glm::vec3& normal() const { return b_.frame.n; }

 private:
  // b_ made in place from what `make` returns (no copy of the text's Bsdf: a path
  // makes one a bounce, and its copy showed in the course room's profile).
  template <typename Make>
  explicit Bsdf(Make&& make) : b_(make()) {}
  brdf::Bsdf b_;
};

}  // namespace engine::rt
