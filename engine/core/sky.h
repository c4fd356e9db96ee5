#pragma once
// The gradient sky of shaders/common/sky.glsl, compiled as C++: the CPU tracers'
// environment (raytrace/environment.cpp) draws the rasterizer's and the GPU tracers'
// sky with their text (tests/core/shading_texts_test.cpp compares the two compiles).
#include <cmath>

#include <glm/glm.hpp>

namespace engine::skytext {
// GLSL's built-ins and types, for the included text only (as core/brdf.h does).
using glm::mix;
using glm::smoothstep;
using glm::vec3;
// The text's square root is GLSL's pow(x, 0.5), which the rasterizer's goldens were
// made with. The CPU tracers have always taken std::sqrt, the correctly rounded root
// (libm's powf differs from it in the last bit for some 0.06 % of [0, 1]), and keep it.
inline float pow(float x, float e) { return e == 0.5f ? std::sqrt(x) : std::pow(x, e); }

#define BRDF_INLINE inline
#include "common/sky.glsl"
#undef BRDF_INLINE
}  // namespace engine::skytext
