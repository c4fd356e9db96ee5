#version 450 core
// tests/render/vertex_runs_gl_test.cpp: a mesh's normals as colours, with depth, so
// that any vertex its runs copy wrong shows in the pixels.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_viewProjection;
out vec3 v_normal;

void main() {
  v_normal = a_normal;
  gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
