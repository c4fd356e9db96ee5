#pragma once
// The phase functions of participating media (shaders/common/phase.glsl) compiled as
// C++: Henyey-Greenstein and Rayleigh, each with its sampling, for the CPU path
// tracer's media; the GPU's compile of the same text is compared with this one in
// tests/core/shading_texts_test.cpp.
#include <cmath>

#include <glm/glm.hpp>

#include "core/brdf.h"

namespace engine::brdf {
using std::abs;
#define BRDF_INLINE inline
#define precise
#include "common/phase.glsl"
#undef precise
#undef BRDF_INLINE
}  // namespace engine::brdf
