#version 450 core
// tests/gputrace/gpu_bsdf_test.cpp: the GPU path tracer's scattering (common/bsdf.glsl
// through rt/bsdf.glsl) at given materials, normals, directions and random numbers,
// so that the C++ build of the same text (raytrace/bsdf.h's Bsdf) can be compared
// case by case.
#include "rt/math.glsl"
#include "rt/sky.glsl"
#include "rt/materials.glsl"
#include "common/brdf.glsl"
#include "common/sampling.glsl"
#include "rt/environment_light.glsl"
#include "rt/view_layers.glsl"
#include "rt/bsdf.glsl"

layout(local_size_x = 64) in;

struct Case {
  ivec4 material;  // x: rtMaterials' index; y: 1 for metallic-roughness, 0 classic; z: entering
  vec4 n, wo, wi;  // unit
  vec4 u;          // xy: the direction's numbers, z: the lobe's
};
struct Answer {
  vec4 f;       // xyz: f(wi); w: pdf(wi)
  vec4 drawn;   // xyz: the sample's wi; w: its pdf
  vec4 weight;  // xyz: its weight; w: 1 when it drew something, 2 when a delta, 3 a delta through
  vec4 shares;  // pSpecular, pSheen, pCoat, pMirror
};

layout(std430, binding = BUFFER_RT_INPUT) readonly buffer Cases { Case cases[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Answers { Answer answers[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  Bsdf b = bsdfOf(rtMaterials[c.material.x], c.material.y != 0, c.n.xyz, c.wo.xyz, c.material.z != 0);
  Answer a;
  a.f = vec4(bsdfF(b, c.wi.xyz), bsdfPdf(b, c.wi.xyz));
  BsdfSample s;
  bool drawn = bsdfSample(b, c.u.xy, c.u.z, s);
  a.drawn = vec4(s.wi, s.pdf);
  a.weight = vec4(s.weight, drawn ? (s.delta ? (s.transmitted ? 3.0 : 2.0) : 1.0) : 0.0);
  a.shares = vec4(b.pSpecular, b.pSheen, b.pCoat, b.pMirror);
  answers[i] = a;
}
