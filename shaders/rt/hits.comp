#version 450 core
// tests/gputrace/gpu_trace_test.cpp: one ray per invocation through rt/trace.glsl, its
// closest hit and whether any hit exists, for comparison with the CPU's RtScene.
#include "rt/trace.glsl"

layout(local_size_x = 64) in;

struct RtQuery {
  vec4 origin;     // xyz; w: tMax
  vec4 direction;  // xyz
};
struct RtAnswer {
  float t;      // the closest hit's, or tMax
  int kind;     // RT_NONE, RT_SPHERE, RT_PLANE, RT_TRIANGLE
  uint index;   // the shape, or the triangle's global id
  uint anyHit;  // 1 when rtAnyHit says so
};

layout(std430, binding = BUFFER_RT_INPUT) readonly buffer Queries { RtQuery queries[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Answers { RtAnswer answers[]; };

uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  RtQuery q = queries[i];
  RtHit hit = rtClosestHit(q.origin.xyz, q.direction.xyz, q.origin.w);
  answers[i] = RtAnswer(hit.t, hit.kind, hit.index, rtAnyHit(q.origin.xyz, q.direction.xyz, q.origin.w) ? 1u : 0u);
}
