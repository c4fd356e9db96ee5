#version 450 core
// tests/gputrace/gpu_material_test.cpp: rtMaterialAt (rt/material_at.glsl), the GPU
// tracers' material at a hit, for given hits (material, uv sets, footprint, shading
// normal, uv gradient, height, vertex colour), so that RtScene::materialAt can be
// compared case by case. Built with rt/trace.glsl's constants and RT_TEXTURES.
#include "rt/trace.glsl"
#include "rt/materials.glsl"
#include "common/brdf.glsl"
#include "rt/surface.glsl"
#include "rt/texture.glsl"
#include "rt/material_at.glsl"

layout(local_size_x = 64) in;

struct Case {
  ivec4 material;    // x: rtMaterials' index
  vec4 uv;           // TEXCOORD_0, TEXCOORD_1
  vec4 nsFootprint;  // the unit shading normal; w: the ray cone's footprint
  vec4 dpdu;         // w: the hit's height
  vec4 dpdv;
  vec4 color;        // COLOR_0
};

layout(std430, binding = BUFFER_RT_INPUT) readonly buffer Cases { Case cases[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Answers { RtMaterial answers[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  Surface s;
  s.p = vec3(0.0, c.dpdu.w, 0.0);
  s.pError = vec3(0.0);
  s.n = c.nsFootprint.xyz;
  s.ns = c.nsFootprint.xyz;
  s.material = c.material.x;
  s.uv0 = c.uv.xy;
  s.uv1 = c.uv.zw;
  s.uvPerMetre = 0.0;
  s.color = c.color;
  s.dpdu = c.dpdu.xyz;
  s.dpdv = c.dpdv.xyz;
  answers[i] = rtMaterialAt(s, c.nsFootprint.w);
}
