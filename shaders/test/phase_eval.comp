#version 450 core
// tests/core/shading_texts_test.cpp: the phase functions (common/phase.glsl) on the
// GPU's compiler, for random inputs, so that the C++ build of the same text
// (core/phase.h) can be compared case by case.
#include "common/brdf.glsl"
#include "common/phase.glsl"

layout(local_size_x = 64) in;

// x: a cosine; y: g; zw: two uniform numbers.
layout(std430, binding = 0) readonly buffer Cases { vec4 cases[]; };
struct Result {
  vec4 values;       // x: Henyey-Greenstein, y: Rayleigh, z, w: the two sampled cosines
  vec4 henyeyGreenstein;  // xyz: the sampled direction
  vec4 rayleigh;          // xyz: the sampled direction
};
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  vec4 c = cases[i];
  Result r;
  r.values = vec4(phaseHenyeyGreenstein(c.x, c.y), phaseRayleigh(c.x), sampleHenyeyGreensteinCosine(c.z, c.y),
                  sampleRayleighCosine(c.z));
  r.henyeyGreenstein = vec4(samplePhaseHenyeyGreenstein(c.zw, c.y), 0.0);
  r.rayleigh = vec4(samplePhaseRayleigh(c.zw), 0.0);
  results[i] = r;
}
