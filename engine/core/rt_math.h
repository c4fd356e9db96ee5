#pragma once
// What shaders/rt/math.glsl gives the GPU's side of the texts that C++ compiles too
// (common/sampling.glsl, common/view_layers.glsl, common/bsdf.glsl): glm's dot,
// cross, normalize, mix and refract, in glm's order, here glm's own. On the GPU the
// text's `precise` keeps the compiler from fusing a multiply and an add; C++ has no
// such qualifier and rounds every operation as written where it does not contract (engine_raytrace, and
// whatever includes its headers, is built with -ffp-contract=off; x86-64's baseline
// has no FMA to contract into).
#include <glm/glm.hpp>

namespace engine::brdf {
inline float rtDot(glm::vec3 a, glm::vec3 b) { return glm::dot(a, b); }
inline glm::vec3 rtCross(glm::vec3 a, glm::vec3 b) { return glm::cross(a, b); }
inline glm::vec3 rtNormalize(glm::vec3 v) { return glm::normalize(v); }
inline float mixAsGlm(float a, float b, float t) { return glm::mix(a, b, t); }
inline glm::vec3 mixAsGlm(glm::vec3 a, glm::vec3 b, float t) { return glm::mix(a, b, t); }
inline glm::vec3 refractAsGlm(glm::vec3 i, glm::vec3 n, float eta) { return glm::refract(i, n, eta); }
}  // namespace engine::brdf
