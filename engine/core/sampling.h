#pragma once
// The path tracers' sampling routines of shaders/common/sampling.glsl, compiled as
// C++ beside the BRDF they sample (core/brdf.h): the CPU path tracer
// (raytrace/sampling.h wraps them in its own names), the split-sum table
// (core/ibl_tables.cpp) and the GPU path tracer evaluate one text
// (tests/core/shading_texts_test.cpp checks that the GPU's compiler gives the same bits, but
// for what comes through GLSL's cos and sin).
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "core/brdf.h"
#include "core/rt_math.h"

namespace engine::brdf {
// GLSL's built-ins the included text uses, beyond brdf.h's. std::abs, not glm::abs:
// GLSL's abs(-0) is +0, as std::abs's, and std::abs is one instruction.
using std::abs;
inline std::uint32_t floatBitsToUint(float x) { return std::bit_cast<std::uint32_t>(x); }
inline float uintBitsToFloat(std::uint32_t x) { return std::bit_cast<float>(x); }

#define BRDF_INLINE inline
#define precise
#include "common/sampling.glsl"
#undef precise
#undef BRDF_INLINE
}  // namespace engine::brdf

namespace engine {
// The GGX sampling the path tracer (raytrace/sampling.h) and the split-sum table
// (core/ibl_tables.cpp) share, under the names they have always called it by.
using brdf::ggxAnisotropicG1;
using brdf::ggxAnisotropicLambda;
using brdf::ggxLambda;
using brdf::ggxSmithG1;
using brdf::sampleGgxAnisotropicVisibleNormal;
using brdf::sampleGgxVisibleNormal;
}  // namespace engine
