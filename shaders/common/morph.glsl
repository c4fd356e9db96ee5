// Morph targets on the GPU (glTF: applied before skinning), for primitives drawn
// with the MORPH variant. Each such primitive has one storage buffer of its
// displacements, vertex-major (vertex v's displacement by target t is the vec4
// block + v * u_morphTargets + t, xyz; w pads), one block per attribute that some target
// moves; u_morphPositions, u_morphNormals and u_morphTangents say where each block
// starts (-1: no target moves it). The weights of every morphing node of the
// model share a second buffer; this node's start at u_morphFirst.
layout(binding = UNIT_MORPH_DELTAS) uniform samplerBuffer u_morphDeltas;
layout(std430, binding = BUFFER_MORPH_WEIGHTS) readonly buffer MorphWeights { float u_morphWeights[]; };

uniform int u_morphTargets;
uniform int u_morphFirst;
uniform int u_morphPositions = -1;
uniform int u_morphNormals = -1;
uniform int u_morphTangents = -1;

// The vertex being morphed: skin.comp (SKIN_COMPUTE) defines its own.
#ifndef MORPH_VERTEX
#define MORPH_VERTEX gl_VertexID
#endif

vec3 morphDelta(int block, int target) { return texelFetch(u_morphDeltas, block + MORPH_VERTEX * u_morphTargets + target).xyz; }

// base + sum_t w_t * delta_t, target by target as the CPU's MorphJob adds them;
// targets of zero weight are skipped. The tangent is only morphed for normal maps.
void morph(inout vec3 position, inout vec3 normal, inout vec3 tangent) {
  for (int t = 0; t < u_morphTargets; ++t) {
    float w = u_morphWeights[u_morphFirst + t];
    if (w == 0.0) continue;
    if (u_morphPositions >= 0) position += w * morphDelta(u_morphPositions, t);
    if (u_morphNormals >= 0) normal += w * morphDelta(u_morphNormals, t);
#ifdef NORMAL_MAP
    if (u_morphTangents >= 0) tangent += w * morphDelta(u_morphTangents, t);
#endif
  }
}
