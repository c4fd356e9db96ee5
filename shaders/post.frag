#version 450 core
// HDR to display: exposure, tone map, then the output curve; with supersampling
// each output pixel averages its N x N HDR samples after tone mapping (the course's
// "render larger, average down").
layout(binding = UNIT_HDR) uniform sampler2D u_hdr;
uniform float u_exposure;
uniform int u_toneMap;      // 0 none (clamp), 1 Reinhard, 2 ACES (Narkowicz fit)
uniform int u_outputCurve;  // 0 sRGB, 1 gamma 1/2.2 (the course)
uniform int u_supersample;  // N
layout(location = 0) out vec4 o_color;

vec3 toneMap(vec3 c) {
  c *= u_exposure;
  if (u_toneMap == 1) return c / (1.0 + c);
  if (u_toneMap == 2) return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
  return clamp(c, 0.0, 1.0);
}

vec3 srgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  ivec2 base = ivec2(gl_FragCoord.xy) * u_supersample;
  vec3 sum = vec3(0.0);
  for (int y = 0; y < u_supersample; ++y)
    for (int x = 0; x < u_supersample; ++x) sum += toneMap(texelFetch(u_hdr, base + ivec2(x, y), 0).rgb);
  vec3 c = clamp(sum / float(u_supersample * u_supersample), 0.0, 1.0);
  o_color = vec4(u_outputCurve == 1 ? pow(c, vec3(1.0 / 2.2)) : srgb(c), 1.0);
}
