#version 450 core
// tests/core/shading_texts_test.cpp: a spot's cone (common/spot_cone.glsl) on the
// GPU's compiler, for random inputs, so that the C++ build of the same text
// (core/spot_cone.h) can be compared case by case.
#include "common/spot_cone.glsl"

layout(local_size_x = 64) in;

// x: the cosine toward the light from the axis; y, z: the outer and inner cones' cosines.
layout(std430, binding = 0) readonly buffer Cases { vec4 cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  vec4 c = cases[i];
  results[i] = vec4(spotAttenuation(c.x, c.y, c.z), 0.0, 0.0, 0.0);
}
