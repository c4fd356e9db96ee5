#include "raytrace/bsdf.h"

#include <algorithm>

#include "core/brdf.h"

namespace engine::rt {
namespace {

float mean(const glm::vec3& c) { return (c.x + c.y + c.z) / 3.0f; }

// A lobe choice u in [0, 1) past a share p taken before it, rescaled to [0, 1) again
// (unchanged where p is 0).
float pastShare(float u, float p) { return (u - p) / (1.0f - p); }

}  // namespace

Bsdf::Bsdf(Model model, const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo)
    : model_(model), m_(m), frame_(n), wo_(wo), woLocal_(frame_.toLocal(wo)) {}

Bsdf Bsdf::classic(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo) {
  Bsdf b(Model::Classic, m, n, wo);
  // Samples follow each part's weight, so a 0.8 mirror gets most of them.
  const float rest = m.diffuse * std::max({m.albedo.x, m.albedo.y, m.albedo.z}) + m.specular;
  const float mirror = std::max(m.reflection, 0.0f);
  b.pMirror_ = mirror > 0.0f ? (rest > 0.0f ? mirror / (mirror + rest) : 1.0f) : 0.0f;
  return b;
}

Bsdf Bsdf::metallicRoughness(const HitMaterial& m, const glm::vec3& n, const glm::vec3& wo, bool entering) {
  Bsdf b(Model::MetallicRoughness, m, n, wo);
  b.entering_ = entering;
  b.alpha_ = brdf::ggxAlpha(m.roughness);
  const float cosO = std::clamp(b.woLocal_.z, 0.0f, 1.0f);
  b.view_ = m.atView(n, cosO);
  if (b.view_.anisotropy > 0.0f) {
    // KHR_materials_anisotropy: the local frame's x along the stretch.
    b.frame_ = Frame(n, b.view_.anisotropyT);
    b.woLocal_ = b.frame_.toLocal(wo);
    b.alphas_ = glm::vec2(brdf::anisotropicAlpha(b.alpha_, b.view_.anisotropy), b.alpha_);
  }
  const glm::vec3 f0 = glm::mix(m.dielectricF0, m.albedo, m.metallic);
  const float f90 = m.dielectricF90 + (1.0f - m.dielectricF90) * m.metallic;
  const float fresnel = mean(glm::mix(brdf::schlickFresnel90(f0, f90, cosO), b.view_.iridescenceF, m.iridescence));
  // A sheen dims what lies under it by its albedo scaling.
  const float sheenScale = b.view_.sheenScale;
  const float sheen = brdf::maxComponent(m.sheenColor) * b.view_.sheenAlbedo;
  const float specular = fresnel * sheenScale;
  const float diffuse = mean(m.albedo) * (1.0f - m.metallic) * (1.0f - m.transmission) * (1.0f - fresnel) * sheenScale;
  // Kept inside [0.1, 0.9] while both lobes exist: a lobe never sampled would leave its
  // light to the light samples alone, and MIS could not weigh it.
  b.pSpecular_ = diffuse > 0.0f ? std::clamp(specular / (specular + diffuse), 0.1f, 0.9f) : 1.0f;
  if (sheen > 0.0f) {
    const float under = specular + diffuse;
    b.pSheen_ = under > 0.0f ? std::clamp(sheen / (sheen + under), 0.1f, 0.9f) : 1.0f;
  }
  // The coat reflects clearcoat Fc toward the eye and passes the rest to what lies
  // under it: the base's reflection and the transmission alike.
  const float coat = m.clearcoat > 0.0f ? m.clearcoat * brdf::schlickFresnel(glm::vec3(0.04f), cosO).x : 0.0f;
  if (m.clearcoat > 0.0f) {
    const float base = (1.0f - coat) * (specular + diffuse + sheen);
    b.alphaCoat_ = brdf::ggxAlpha(m.clearcoatRoughness);
    b.pCoat_ = base > 0.0f ? std::clamp(coat / (coat + base), 0.1f, 0.9f) : 1.0f;
  }
  if (m.transmission > 0.0f && m.metallic < 1.0f) {
    const float through =
        mean(m.albedo) * (1.0f - m.metallic) * m.transmission * (1.0f - fresnel) * (1.0f - coat) * sheenScale;
    const float reflected = coat + (1.0f - coat) * (specular + diffuse + sheen);
    b.pTransmit_ = reflected > 0.0f ? std::clamp(through / (through + reflected), 0.1f, 0.9f) : 1.0f;
    // A thin wall blurs what is behind it as much as its ior bends (none at 1);
    // a volume's facets refract at the surface's own roughness.
    b.alphaTransmit_ = brdf::ggxAlpha(m.thickness > 0.0f ? m.roughness : brdf::transmissionRoughness(m.roughness, m.ior));
  }
  return b;
}

glm::vec3 Bsdf::f(const glm::vec3& wi) const {
  const float cosI = glm::dot(frame_.n, wi);
  if (cosI <= 0.0f || woLocal_.z <= 0.0f) return glm::vec3(0.0f);
  if (model_ == Model::Classic) {
    // Without a highlight classicReflected / (pi N.L) is the Lambert term exactly.
    if (m_.specular <= 0.0f) return m_.albedo * (m_.diffuse / brdf::BRDF_PI);
    const glm::vec3 reflected =
        brdf::classicReflected(frame_.n, wo_, wi, m_.albedo, m_.diffuse, m_.specular, m_.shininess);
    return reflected / (brdf::BRDF_PI * cosI);
  }
  return brdf::layeredBrdf(frame_.n, wo_, wi, m_.albedo, m_.metallic, m_.roughness, m_.dielectricF0,
                           m_.dielectricF90, frame_.n, m_.clearcoat, m_.clearcoatRoughness, m_.transmission,
                           m_.sheenColor, m_.sheenRoughness, view_.sheenScale, frame_.s, frame_.t, view_.anisotropy,
                           view_.iridescenceF, m_.iridescence);
}

float Bsdf::pdf(const glm::vec3& wi) const {
  const glm::vec3 wiLocal = frame_.toLocal(wi);
  if (wiLocal.z <= 0.0f || woLocal_.z <= 0.0f) return 0.0f;
  if (model_ == Model::Classic) return (1.0f - pMirror_) * cosineHemispherePdf(wiLocal.z);
  const float specular = view_.anisotropy > 0.0f ? ggxAnisotropicReflectionPdf(woLocal_, wiLocal, alphas_)
                                            : ggxReflectionPdf(woLocal_, wiLocal, alpha_);
  float base = pSpecular_ * specular + (1.0f - pSpecular_) * cosineHemispherePdf(wiLocal.z);
  if (pSheen_ > 0.0f) base = pSheen_ * uniformConePdf(0.0f) + (1.0f - pSheen_) * base;
  const float reflected = pCoat_ <= 0.0f ? base : pCoat_ * ggxReflectionPdf(woLocal_, wiLocal, alphaCoat_) + (1.0f - pCoat_) * base;
  return (1.0f - pTransmit_) * reflected;
}

std::optional<BsdfSample> Bsdf::sample(glm::vec2 u, float uLobe) const {
  if (woLocal_.z <= 0.0f) return std::nullopt;
  if (model_ == Model::Classic && uLobe < pMirror_) {
    BsdfSample s;
    s.wi = frame_.toWorld(glm::vec3(-woLocal_.x, -woLocal_.y, woLocal_.z));
    s.weight = glm::vec3(m_.reflection / pMirror_);
    s.delta = true;
    return s;
  }
  if (model_ == Model::Classic && m_.specular <= 0.0f) return lambertSample(u);
  if (uLobe < pTransmit_) return transmissionSample(u);
  return reflectionSample(u, pastShare(uLobe, pTransmit_));
}

// The lobes above the surface, uLobe rescaled past the transmission's share.
std::optional<BsdfSample> Bsdf::reflectionSample(glm::vec2 u, float uLobe) const {
  glm::vec3 wiLocal;
  if (model_ == Model::MetallicRoughness && uLobe < pCoat_) {
    wiLocal = reflectAbout(woLocal_, sampleGgxVisibleNormal(woLocal_, alphaCoat_, u));
  } else if (model_ == Model::MetallicRoughness && pastShare(uLobe, pCoat_) < pSheen_) {
    wiLocal = sampleUniformCone(u, 0.0f);
  } else if (model_ == Model::MetallicRoughness && pastShare(pastShare(uLobe, pCoat_), pSheen_) < pSpecular_) {
    const glm::vec3 h = view_.anisotropy > 0.0f ? sampleGgxAnisotropicVisibleNormal(woLocal_, alphas_, u)
                                           : sampleGgxVisibleNormal(woLocal_, alpha_, u);
    wiLocal = reflectAbout(woLocal_, h);
  } else {
    wiLocal = sampleCosineHemisphere(u);
  }
  if (wiLocal.z <= 0.0f) return std::nullopt;  // the facet reflected it below the surface
  BsdfSample s;
  s.wi = glm::normalize(frame_.toWorld(wiLocal));
  s.pdf = pdf(s.wi);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.weight = f(s.wi) * (glm::dot(frame_.n, s.wi) / s.pdf);
  return s;
}

// Through the surface: a GGX visible normal m, and the ray refracted by it into a
// volume (or mirrored by it inside, past the critical angle), or mirrored by it and
// turned through a thin wall. The weight is what the layered model passes,
// (1 - F(wo.m)) times the base colour and transmission, times G1 of the new
// direction (visible-normal sampling leaves no other factor), over the lobe's share.
std::optional<BsdfSample> Bsdf::transmissionSample(glm::vec2 u) const {
  const glm::vec3 m = sampleGgxVisibleNormal(woLocal_, alphaTransmit_, u);
  const float cosO = glm::dot(woLocal_, m);
  if (!(cosO > 0.0f)) return std::nullopt;
  const glm::vec3 fresnel = brdf::schlickFresnel90(m_.dielectricF0, m_.dielectricF90, cosO);
  const glm::vec3 share =
      (glm::vec3(1.0f) - fresnel) * m_.albedo * ((1.0f - m_.metallic) * m_.transmission * view_.sheenScale);
  glm::vec3 wiLocal;
  if (m_.thickness > 0.0f) {
    const float eta = entering_ ? 1.0f / std::max(m_.ior, 1.0f) : std::max(m_.ior, 1.0f);
    wiLocal = glm::refract(-woLocal_, m, eta);
    if (wiLocal == glm::vec3(0.0f)) {
      // Total internal reflection: what the reflection lobe's Fresnel did not take
      // stays inside as well.
      wiLocal = reflectAbout(woLocal_, m);
      if (wiLocal.z <= 0.0f) return std::nullopt;
    } else if (wiLocal.z >= 0.0f) {
      return std::nullopt;
    }
  } else {
    wiLocal = reflectAbout(woLocal_, m);
    if (wiLocal.z <= 0.0f) return std::nullopt;
    wiLocal.z = -wiLocal.z;
  }
  BsdfSample s;
  s.wi = glm::normalize(frame_.toWorld(wiLocal));
  s.weight = share * (ggxSmithG1(std::abs(wiLocal.z), alphaTransmit_) / pTransmit_);
  s.delta = true;
  s.transmitted = wiLocal.z < 0.0f;
  return s;
}

// The course's diffuse alone: f cos / pdf is (albedo diffuse / pi) cos over
// (1 - pMirror) cos / pi, so the weight needs no evaluation (a third of a bounce's
// shading time in the course room).
std::optional<BsdfSample> Bsdf::lambertSample(glm::vec2 u) const {
  const glm::vec3 wiLocal = sampleCosineHemisphere(u);
  if (wiLocal.z <= 0.0f) return std::nullopt;
  BsdfSample s;
  s.wi = frame_.toWorld(wiLocal);
  s.pdf = (1.0f - pMirror_) * cosineHemispherePdf(wiLocal.z);
  s.weight = m_.albedo * (m_.diffuse / (1.0f - pMirror_));
  return s;
}

}  // namespace engine::rt
