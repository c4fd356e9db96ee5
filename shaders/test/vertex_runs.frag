#version 450 core
// tests/render/vertex_runs_gl_test.cpp: see vertex_runs.vert.
in vec3 v_normal;
layout(location = 0) out vec4 o_color;

void main() { o_color = vec4(normalize(v_normal) * 0.5 + 0.5, 1.0); }
