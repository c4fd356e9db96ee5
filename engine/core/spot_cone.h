#pragma once
// A spot light's cone (shaders/common/spot_cone.glsl) compiled as C++: the CPU tracers
// weigh a spot's light with the text the rasterizer and the GPU tracers use
// (tests/core/shading_texts_test.cpp compares the two compiles).
namespace engine::spottext {
#define BRDF_INLINE inline
#include "common/spot_cone.glsl"
#undef BRDF_INLINE
}  // namespace engine::spottext
