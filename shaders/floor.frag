#version 450 core
// The least shading that still reads every triangle's normal: one directional light.
in vec3 v_normal;
uniform vec3 u_sunDirection;
layout(location = 0) out vec4 o_color;
void main() {
  float d = max(dot(normalize(v_normal), u_sunDirection), 0.0);
  o_color = vec4(vec3(0.1 + 0.9 * d), 1.0);
}
