#pragma once
// glTF's layer textures and anisotropy at a tracer's hit
// (shaders/common/layer_texels.glsl) compiled as C++: the CPU tracers
// (raytrace/rt_materials.cpp) and the GPU tracers (rt/material_at.glsl) apply a hit's
// layer texels and orient its stretch with one text.
#include <glm/glm.hpp>

#include "core/brdf.h"
#include "core/rt_math.h"

namespace engine::brdf {
using glm::dvec3;
using glm::isinf;
using glm::isnan;
using glm::min;
using glm::vec4;
#define BRDF_INLINE inline
#define precise
#include "common/layer_texels.glsl"
#undef precise
#undef BRDF_INLINE
#undef LAYER_MIX
}  // namespace engine::brdf
