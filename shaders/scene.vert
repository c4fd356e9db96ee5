#version 450 core
// Every mesh of a scene: analytic primitives, glTF meshes (static, or morphed
// and/or skinned on the GPU), drawn camera-relative.
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

#include "common/frame.glsl"
#include "common/deform.glsl"

uniform mat4 u_model;        // camera offset included
uniform mat3 u_normalMatrix;
uniform vec2 u_uvScale = vec2(1.0);  // texture tiling of analytic shapes
#ifdef DEPTH_ONLY
uniform mat4 u_lightViewProjection;  // shadow passes draw from the light
#endif

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
  v_uv = a_uv * u_uvScale;
#ifdef UV_TRANSFORM
  v_uv1 = a_uv1;
#endif
#ifdef VERTEX_COLOR
  v_color = a_color;
#endif
#ifdef DEPTH_ONLY
  gl_Position = u_lightViewProjection * world;
#else
  gl_Position = u_viewProjection * world;
#endif
}
