#pragma once
// The material models of shaders/common/brdf.glsl, compiled as C++: the rasterizer's
// shaders and the CPU tracers evaluate one text, so a change to either is a change to
// both (tests/core/brdf_test.cpp checks that they agree on the GPU's compiler too).
#include <glm/glm.hpp>

namespace engine::brdf {
// GLSL's built-ins (dot, normalize, mix, max, clamp, sqrt, pow) and types, for the
// included text only.
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::length;
using glm::max;
using glm::mix;
using glm::normalize;
using glm::pow;
using glm::sin;
using glm::sqrt;
using glm::vec2;
using glm::vec3;

#define BRDF_INLINE inline
#include "common/brdf.glsl"
#undef BRDF_INLINE
}  // namespace engine::brdf
