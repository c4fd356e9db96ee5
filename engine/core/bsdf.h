#pragma once
// The path tracers' scattering at one hit (shaders/common/bsdf.glsl) compiled as C++
// beside the BRDF, sampling and view terms it is made of: the CPU path tracer
// (raytrace/bsdf.h wraps it in its Bsdf class) and the GPU path tracer (rt/bsdf.glsl)
// scatter with one text (tests/gputrace/gpu_bsdf_test.cpp compares the two compiles).
#include <cmath>

#include <glm/glm.hpp>

#include "core/brdf.h"
#include "core/rt_math.h"
#include "core/sampling.h"
#include "core/view_layers.h"

namespace engine::brdf {
#define BRDF_INLINE inline
#define BRDF_IN(T) const T&
#define precise
#include "common/bsdf.glsl"
#undef precise
#undef BRDF_IN
#undef BRDF_INLINE
}  // namespace engine::brdf
