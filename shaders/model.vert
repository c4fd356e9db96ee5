#version 450 core
// glTF meshes: static, or morphed and/or skinned on the GPU (see common/deform.glsl). For a
// skinned mesh u_model is the model's root, camera-relative: the palette places the
// vertices in model space, and glTF says the mesh node's own transform is ignored.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
#ifdef UV_TRANSFORM
layout(location = 8) in vec2 a_uv1;  // TEXCOORD_1 (common/material.glsl)
out vec2 v_uv1;
#endif
#ifdef VERTEX_COLOR
layout(location = 9) in vec4 a_color;  // COLOR_0 (common/material.glsl)
out vec4 v_color;
#endif

#include "common/deform.glsl"

uniform mat4 u_model;
uniform mat3 u_normalMatrix;
uniform mat4 u_viewProjection;

out vec3 v_position;  // camera-relative world position
out vec3 v_normal;
out vec2 v_uv;

void main() {
  vec3 position = a_position;
  vec3 normal = a_normal;
  deform(position, normal, u_model);
  vec4 world = u_model * vec4(position, 1.0);
  v_position = world.xyz;
  v_normal = u_normalMatrix * normal;
  v_uv = a_uv;
#ifdef UV_TRANSFORM
  v_uv1 = a_uv1;
#endif
#ifdef VERTEX_COLOR
  v_color = a_color;
#endif
  gl_Position = u_viewProjection * world;
}
