#pragma once
// The view's terms of glTF's layers (shaders/common/view_layers.glsl) compiled as
// C++ beside the BRDF that takes them (core/brdf.h): the CPU tracers
// (HitMaterial::atView, raytrace/rt_scene.h) and the GPU tracers
// (rt/view_layers.glsl) work them out with one text.
#include <glm/glm.hpp>

#include "core/brdf.h"
#include "core/rt_math.h"

namespace engine::brdf {
#define BRDF_INLINE inline
#define precise
#include "common/view_layers.glsl"
#undef precise
#undef BRDF_INLINE
}  // namespace engine::brdf
