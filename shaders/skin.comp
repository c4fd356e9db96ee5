#version 450 core
// The skin cache (render/skin_cache.h): morphs and skins every vertex of one
// primitive instance once per pose, with the very functions model.vert and
// scene.vert run per vertex (common/morph.glsl, common/skinning.glsl), and writes
// the result where every pass then reads it as a static mesh. Variants: SKINNED
// (INFLUENCES 4 or 8, DUAL_QUAT), MORPH, HAS_NORMALS, NORMAL_MAP (the mesh has
// tangents: they are deformed like the normal, their w kept).
layout(local_size_x = 64) in;

#define SKIN_COMPUTE 1

// The primitive's own vertex buffers (render/model_renderer.cpp's upload): tight
// vec3 positions and normals, vec4 tangents, INFLUENCES uint16 joints and floats
// per vertex.
layout(std430, binding = BUFFER_SKIN_POSITIONS) readonly buffer InPositions { float in_positions[]; };
#ifdef HAS_NORMALS
layout(std430, binding = BUFFER_SKIN_NORMALS) readonly buffer InNormals { float in_normals[]; };
#endif
#ifdef NORMAL_MAP
layout(std430, binding = BUFFER_SKIN_TANGENTS) readonly buffer InTangents { vec4 in_tangents[]; };
#endif
#ifdef SKINNED
layout(std430, binding = BUFFER_SKIN_JOINTS) readonly buffer InJoints { uint in_joints[]; };
layout(std430, binding = BUFFER_SKIN_WEIGHTS) readonly buffer InWeights { float in_weights[]; };
#endif

// One deformed vertex: what the cached vertex array reads at offsets 0, 16, 32.
struct DeformedVertex {
  vec4 position;
  vec4 normal;
  vec4 tangent;
};
layout(std430, binding = BUFFER_SKIN_OUTPUT) writeonly buffer OutVertices { DeformedVertex out_vertices[]; };

uniform int u_vertexCount;

uint g_vertex;  // this invocation's vertex

#ifdef SKINNED
// Group k of four joints (two uint16 per uint) and of four weights.
uvec4 vertexJoints(uint k) {
  uint base = (g_vertex * uint(INFLUENCES) + 4u * k) / 2u;
  uint a = in_joints[base], b = in_joints[base + 1u];
  return uvec4(a & 0xFFFFu, a >> 16, b & 0xFFFFu, b >> 16);
}
vec4 vertexWeights(uint k) {
  uint base = g_vertex * uint(INFLUENCES) + 4u * k;
  return vec4(in_weights[base], in_weights[base + 1u], in_weights[base + 2u], in_weights[base + 3u]);
}
#define a_joints0 vertexJoints(0u)
#define a_weights0 vertexWeights(0u)
#define a_joints1 vertexJoints(1u)
#define a_weights1 vertexWeights(1u)
#include "common/skinning.glsl"
#endif

#ifdef MORPH
#define MORPH_VERTEX int(g_vertex)
#include "common/morph.glsl"
#endif

vec3 readVec3(uint i, bool normal) {
#ifdef HAS_NORMALS
  if (normal) return vec3(in_normals[3u * i], in_normals[3u * i + 1u], in_normals[3u * i + 2u]);
#else
  if (normal) return vec3(0.0, 1.0, 0.0);  // the vertex arrays' constant attribute
#endif
  return vec3(in_positions[3u * i], in_positions[3u * i + 1u], in_positions[3u * i + 2u]);
}

void main() {
  g_vertex = gl_GlobalInvocationID.x;
  if (int(g_vertex) >= u_vertexCount) return;
  vec3 position = readVec3(g_vertex, false);
  vec3 normal = readVec3(g_vertex, true);
#ifdef NORMAL_MAP
  vec4 tangent = in_tangents[g_vertex];
#else
  vec4 tangent = vec4(0.0);
#endif
  vec3 t = tangent.xyz;
#ifdef MORPH
  morph(position, normal, t);
#endif
#ifdef SKINNED
  skin(position, normal, t);
#endif
  out_vertices[g_vertex] = DeformedVertex(vec4(position, 1.0), vec4(normal, 0.0), vec4(t, tangent.w));
}
