#include "raytrace/bsdf.h"

namespace engine::rt {
namespace {

// What the text's scattering takes of a hit's material.
brdf::BsdfMaterial scatteringOf(const HitMaterial& m) {
  brdf::BsdfMaterial s;
  s.albedo = m.albedo;
  s.diffuse = m.diffuse;
  s.specular = m.specular;
  s.shininess = m.shininess;
  s.reflection = m.reflection;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  s.dielectricF0 = m.dielectricF0;
  s.dielectricF90 = m.dielectricF90;
  s.clearcoat = m.clearcoat;
  s.clearcoatRoughness = m.clearcoatRoughness;
  s.sheenColor = m.sheenColor;
  s.sheenRoughness = m.sheenRoughness;
  s.iridescence = m.iridescence;
  s.transmission = m.transmission;
  s.ior = m.ior;
  s.thickness = m.thickness;
  return s;
}

}  // namespace

Bsdf Bsdf::classic(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo) {
  return Bsdf([&] { return brdf::bsdfAbout(scatteringOf(m), false, n, wo, true); });
}

Bsdf Bsdf::metallicRoughness(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo, bool entering) {
  return Bsdf([&] {
    const brdf::Bsdf b = brdf::bsdfAbout(scatteringOf(m), true, n, wo, entering);
    return brdf::bsdfViewed(b, n, m.atView(n, brdf::bsdfCosView(b)));
  });
}

}  // namespace engine::rt
