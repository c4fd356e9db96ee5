#version 450 core
// The skin cache (render/skin_cache.h): morphs and skins every vertex of one
// primitive instance once per pose, with the very functions scene.vert runs per
// vertex (common/morph.glsl, common/skinning.glsl), and writes
// the result where every pass then reads it as a static mesh. Variants: SKINNED
// (INFLUENCES 4 or 8, DUAL_QUAT), MORPH, HAS_NORMALS, NORMAL_MAP (the mesh has
// tangents: they are deformed like the normal, their w kept).
layout(local_size_x = 64) in;

#define SKIN_COMPUTE 1

// The primitive's own vertex buffers (render/model_renderer.cpp's upload) as
// buffer textures (gl::Texture::ofBuffer says why): tight vec3 positions and
// normals (RGB32F), vec4 tangents, INFLUENCES uint16 joints (RGBA16UI: four a
// texel) and floats (RGBA32F) per vertex.
layout(binding = UNIT_SKIN_POSITIONS) uniform samplerBuffer in_positions;
#ifdef HAS_NORMALS
layout(binding = UNIT_SKIN_NORMALS) uniform samplerBuffer in_normals;
#endif
#ifdef NORMAL_MAP
layout(binding = UNIT_SKIN_TANGENTS) uniform samplerBuffer in_tangents;
#endif
#ifdef SKINNED
layout(binding = UNIT_SKIN_JOINTS) uniform usamplerBuffer in_joints;
layout(binding = UNIT_SKIN_WEIGHTS) uniform samplerBuffer in_weights;
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
// Group k of four joints and of four weights: texel k of the vertex's.
uvec4 vertexJoints(uint k) { return texelFetch(in_joints, int(g_vertex * uint(INFLUENCES / 4) + k)); }
vec4 vertexWeights(uint k) { return texelFetch(in_weights, int(g_vertex * uint(INFLUENCES / 4) + k)); }
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

vec3 readNormal(uint i) {
#ifdef HAS_NORMALS
  return texelFetch(in_normals, int(i)).xyz;
#else
  return vec3(0.0, 1.0, 0.0);  // the vertex arrays' constant attribute
#endif
}

void main() {
  g_vertex = gl_GlobalInvocationID.x;
  if (int(g_vertex) >= u_vertexCount) return;
  vec3 position = texelFetch(in_positions, int(g_vertex)).xyz;
  vec3 normal = readNormal(g_vertex);
#ifdef NORMAL_MAP
  vec4 tangent = texelFetch(in_tangents, int(g_vertex));
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
