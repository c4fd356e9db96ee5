#version 450 core
// tests/core/shading_texts_test.cpp: the anisotropy's stretch at a hit
// (common/layer_texels.glsl's orientedAnisotropy) on the GPU's compiler, for random
// and degenerate uv gradients, so that the C++ build (core/layer_texels.h) can be
// compared case by case.
#include "rt/math.glsl"
#include "common/brdf.glsl"
#include "common/layer_texels.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 ns;         // xyz: the unit shading normal; w: the strength
  vec4 dpdu;       // xyz; w: the rotation
  vec4 dpdv;       // xyz
  vec4 direction;  // xy
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  results[i] = orientedAnisotropy(c.direction.xy, c.dpdu.w, c.ns.w, c.ns.xyz, c.dpdu.xyz, c.dpdv.xyz);
}
