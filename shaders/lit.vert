#version 450 core
// Static, lit, textured meshes. Positions arrive camera-relative: u_model already
// has the camera position subtracted (in double on the CPU), so far from the origin
// nothing large is ever stored in a float.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;

uniform mat4 u_model;
uniform mat3 u_normalMatrix;
uniform mat4 u_viewProjection;

out vec3 v_position;  // camera-relative world position
out vec3 v_normal;
out vec2 v_uv;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_position = world.xyz;
  v_normal = u_normalMatrix * a_normal;
  v_uv = a_uv;
  gl_Position = u_viewProjection * world;
}
