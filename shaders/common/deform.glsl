// What scene.vert does to a glTF vertex before placing it: morph
// targets (MORPH), then skinning (SKINNED), in glTF's order. The tangent of a
// normal-mapped mesh goes through both like the normal, then to world space by
// `model` (common/mesh_tangent.glsl).
#ifdef MORPH
#include "common/morph.glsl"
#endif
#ifdef SKINNED
#include "common/skinning.glsl"
#endif
#include "common/mesh_tangent.glsl"

void deform(inout vec3 position, inout vec3 normal, mat4 model) {
#ifdef MESH_TANGENT
  vec3 tangent = a_tangent.xyz;
#else
  vec3 tangent = vec3(0.0);
#endif
#ifdef MORPH
  morph(position, normal, tangent);
#endif
#if defined(SKINNED) && defined(MESH_TANGENT)
  skin(position, normal, tangent);
#elif defined(SKINNED)
  skin(position, normal);
#endif
#ifdef MESH_TANGENT
  setTangent(tangent, model);
#endif
}
