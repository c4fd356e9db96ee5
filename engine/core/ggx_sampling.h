#pragma once
// GGX sampling that the path tracer (raytrace/sampling.h, whose chi-square tests
// cover these) and the split-sum BRDF table (core/ibl_tables.cpp) share; the GPU path
// tracer's transcription is shaders/rt/sampling.glsl. Local
// frame: the normal along +z.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace engine {

// GGX's Smith Lambda for a direction at cos theta (the same Lambda as brdf.glsl's
// height-correlated visibility): G1 = 1 / (1 + Lambda).
inline float ggxLambda(float cosTheta, float alpha) {
  const float c2 = std::max(cosTheta * cosTheta, 1e-12f);
  const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}
inline float ggxSmithG1(float cosTheta, float alpha) { return 1.0f / (1.0f + ggxLambda(cosTheta, alpha)); }

// KHR_materials_anisotropy's GGX, alpha.x along the local x axis and alpha.y along y
// (Heitz 2014 and 2018 with two roughnesses). Lambda is kept apart from the
// isotropic form above, which every other material's images were made with.
inline float ggxAnisotropicLambda(const glm::vec3& w, glm::vec2 alpha) {
  const float z2 = std::max(w.z * w.z, 1e-12f);
  const float a2Tan2 = (alpha.x * alpha.x * w.x * w.x + alpha.y * alpha.y * w.y * w.y) / z2;
  return 0.5f * (std::sqrt(1.0f + a2Tan2) - 1.0f);
}
inline float ggxAnisotropicG1(const glm::vec3& w, glm::vec2 alpha) { return 1.0f / (1.0f + ggxAnisotropicLambda(w, alpha)); }

inline glm::vec3 sampleGgxAnisotropicVisibleNormal(const glm::vec3& wo, glm::vec2 alpha, glm::vec2 u) {
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha.x * wo.x, alpha.y * wo.y, wo.z));
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha.x * nh.x, alpha.y * nh.y, std::max(1e-6f, nh.z)));
}

// A microfacet normal drawn from the normals visible from wo (Heitz, "Sampling the
// GGX Distribution of Visible Normals", JCGT 2018): no sample is wasted on facets
// that face away, so grazing views stay as cheap as head-on ones. wo.z > 0. The
// anisotropic sampler with equal alphas: the same operations, the same bits.
inline glm::vec3 sampleGgxVisibleNormal(const glm::vec3& wo, float alpha, glm::vec2 u) {
  return sampleGgxAnisotropicVisibleNormal(wo, glm::vec2(alpha), u);
}

}  // namespace engine
