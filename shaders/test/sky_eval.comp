#version 450 core
// tests/core/shading_texts_test.cpp: the gradient sky (common/sky.glsl) on the GPU's
// compiler, for random inputs, so that the C++ build of the same text (core/sky.h)
// can be compared case by case.
#include "common/sky.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 d;        // xyz: a unit direction; w: the cosine toward the sun
  vec4 horizon;  // xyz; w: 1 to draw the sun's disk, 0 not
  vec4 zenith;   // xyz
  vec4 ground;   // xyz
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  results[i] = vec4(gradientSky(c.d.xyz, c.horizon.xyz, c.zenith.xyz, c.ground.xyz, c.d.w, c.horizon.w), 0.0);
}
