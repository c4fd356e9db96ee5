#version 450 core
// One group of the flattened scene refitted in place (gputrace/gpu_refit.h): its
// leaves' vertices and its triangles' normals from new vertices, then its nodes'
// boxes level by level from the deepest up, then its instance's bounds: what
// Bvh::refit and flattenScene make on the CPU, and the same bits (min and max of the
// same floats; an empty slot's box, min +inf and max -inf, changes neither).
// u_stage picks the step; one dispatch per step, and per level of nodes.
#include "rt/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BUFFER_RT_NODES) buffer RtNodes { RtNode nodes[]; };
layout(std430, binding = BUFFER_RT_LEAVES) buffer RtLeaves { RtLeaf leaves[]; };
layout(std430, binding = BUFFER_RT_INSTANCES) buffer RtInstances { RtInstance instances[]; };
layout(std430, binding = BUFFER_RT_TRIANGLES) buffer RtTriangles { RtTriangle triangles[]; };
// The group's vertices, u_stride vec4 apart: position, then normal.
layout(std430, binding = BUFFER_RT_INPUT) readonly buffer Vertices { vec4 vertices[]; };
// GpuRefitPlan's tables, one after another; a stage reads u_count entries from u_first.
layout(std430, binding = BUFFER_RT_REFIT_PLAN) readonly buffer Plan { uvec4 plan[]; };

const int STAGE_LEAVES = 0;     // one invocation a leaf; u_base: the group's first leaf
const int STAGE_TRIANGLES = 1;  // one a triangle; u_base: its first global triangle id
const int STAGE_NODES = 2;      // one a node of a level (plan[].x)
const int STAGE_INSTANCE = 3;   // one; u_base: the instance

uniform int u_stage;
uniform uint u_first;
uniform uint u_count;
uniform uint u_base;
uniform uint u_stride;

vec3 position(uint v) { return vertices[v * u_stride].xyz; }
vec3 normal(uint v) { return vertices[v * u_stride + 1u].xyz; }

void refitLeaf(uint i) {
  vec4 p[9];
  for (int k = 0; k < 9; ++k) p[k] = vec4(0.0);  // empty lanes stay zero, as Bvh's
  for (int lane = 0; lane < 4; ++lane) {
    uvec4 c = plan[u_first + 4u * i + uint(lane)];
    if (c.w == 0u) continue;
    for (int v = 0; v < 3; ++v) {
      vec3 x = position(c[v]);
      for (int axis = 0; axis < 3; ++axis) p[3 * v + axis][lane] = x[axis];
    }
  }
  leaves[u_base + i].p = p;
}

void refitTriangle(uint t) {
  uvec4 c = plan[u_first + t];
  if (c.w == 0u) return;
  for (int v = 0; v < 3; ++v) triangles[u_base + t].n[v].xyz = normal(c[v]);
}

// The box of what a reference holds: a leaf's triangles, or a node's slots.
void boundsOf(uint ref, out vec3 lo, out vec3 hi) {
  lo = vec3(uintBitsToFloat(0x7f800000u));
  hi = -lo;
  if ((ref & RT_LEAF_BIT) != 0u) {
    uint leaf = ref & (RT_MAX_TRIANGLES - 1u);
    int count = int((ref >> 28) & 3u) + 1;
    for (int lane = 0; lane < count; ++lane) {
      for (int v = 0; v < 3; ++v) {
        vec3 x = vec3(leaves[leaf].p[3 * v][lane], leaves[leaf].p[3 * v + 1][lane], leaves[leaf].p[3 * v + 2][lane]);
        lo = min(lo, x);
        hi = max(hi, x);
      }
    }
    return;
  }
  for (int side = 0; side < RT_SIDES; ++side) {
    for (int axis = 0; axis < 3; ++axis) {
      vec4 mins = nodes[ref].box[RT_SIDES * axis + side], maxs = nodes[ref].box[RT_SIDES * (3 + axis) + side];
      lo[axis] = min(lo[axis], min(min(mins.x, mins.y), min(mins.z, mins.w)));
      hi[axis] = max(hi[axis], max(max(maxs.x, maxs.y), max(maxs.z, maxs.w)));
    }
  }
}

void refitNode(uint node) {
  for (int slot = 0; slot < RT_WIDTH; ++slot) {
    int side = slot / 4, k = slot % 4;
    uint ref = nodes[node].child[side][k];
    if (ref == RT_NO_CHILD) continue;
    vec3 lo, hi;
    boundsOf(ref, lo, hi);
    for (int axis = 0; axis < 3; ++axis) {
      nodes[node].box[RT_SIDES * axis + side][k] = lo[axis];
      nodes[node].box[RT_SIDES * (3 + axis) + side][k] = hi[axis];
    }
  }
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  if (u_stage == STAGE_LEAVES) {
    refitLeaf(i);
  } else if (u_stage == STAGE_TRIANGLES) {
    refitTriangle(i);
  } else if (u_stage == STAGE_NODES) {
    refitNode(plan[u_first + i].x);
  } else {
    vec3 lo, hi;
    boundsOf(instances[u_base].root.x, lo, hi);
    instances[u_base].boundsMin = vec4(lo, 0.0);
    instances[u_base].boundsMax = vec4(hi, 0.0);
  }
}
