#pragma once
// shaders/common/ibl_sampling.glsl compiled as C++, beside the BRDF it samples
// (core/brdf.h): the CPU's BRDF table and SH projection and the GPU's prefilter use
// one Hammersley set, one GGX sampler, one cube-face mapping and one SH basis.
#include "core/brdf.h"

namespace engine::brdf {
using uint = unsigned;
using glm::abs;
using glm::cos;
using glm::sin;
using glm::vec2;

#define BRDF_INLINE inline
#include "common/ibl_sampling.glsl"
#undef BRDF_INLINE
}  // namespace engine::brdf
