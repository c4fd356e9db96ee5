#version 450 core
// Analytic sky: a gradient from horizon to zenith, a darker ground and a sun disk.
in vec3 v_direction;
uniform vec3 u_sunDirection;
uniform vec3 u_skyColor;
uniform vec3 u_horizonColor;
uniform vec3 u_groundColor;
layout(location = 0) out vec4 o_color;

void main() {
  vec3 d = normalize(v_direction);
  vec3 color = d.y >= 0.0 ? mix(u_horizonColor, u_skyColor, pow(d.y, 0.5))
                          : mix(u_horizonColor, u_groundColor, pow(-d.y, 0.5));
  float sun = smoothstep(0.9995, 0.9998, dot(d, u_sunDirection));
  color += vec3(4.0, 3.6, 3.0) * sun;
#ifdef HDR_OUTPUT
  o_color = vec4(color, 1.0);  // the post pass tone maps
#else
  o_color = vec4(color / (1.0 + color), 1.0);
#endif
}
