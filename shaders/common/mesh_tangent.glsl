// The TANGENT attribute of normal-mapped meshes (scene.vert): xyz
// skinned like the normal when the mesh is skinned, then taken to world space by
// the model matrix (a tangent lies in the surface, so the matrix itself, not its
// inverse transpose). A mirroring model matrix flips the bitangent's handedness.
// The clear coat's own normal map (CLEARCOAT_NORMAL) and anisotropy (ANISOTROPY)
// need it as well.
#if defined(NORMAL_MAP) || defined(CLEARCOAT_NORMAL) || defined(ANISOTROPY)
#define MESH_TANGENT 1
#endif
#ifdef MESH_TANGENT
layout(location = 7) in vec4 a_tangent;
out vec4 v_tangent;

void setTangent(vec3 tangent, mat4 model) {
  mat3 m = mat3(model);
  float mirror = determinant(m) < 0.0 ? -1.0 : 1.0;
  v_tangent = vec4(m * tangent, a_tangent.w * mirror);
}
#endif
