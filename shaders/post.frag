#version 450 core
// HDR to display: exposure, tone map, then the output curve (common/output.glsl,
// which DIRECT_OUTPUT's fragment shaders apply themselves); with supersampling
// each output pixel averages its N x N HDR samples after tone mapping (the course's
// "render larger, average down"). The scene renderer builds the one variant its
// settings need: SUPERSAMPLE N, TONE_MAP 0 none (clamp) / 1 Reinhard / 2 ACES
// (Narkowicz fit), OUTPUT_GAMMA22 (the course's 1/2.2; else sRGB). As uniforms,
// with a loop of a uniform trip count, llvmpipe took 26 ms a 1280x720 frame for
// this pass; specialised, 12 ms, the same bytes.
layout(binding = UNIT_HDR) uniform sampler2D u_hdr;
uniform float u_exposure;
layout(location = 0) out vec4 o_color;

#ifndef SUPERSAMPLE
#define SUPERSAMPLE 1
#endif

#include "common/output.glsl"

vec3 toneMap(vec3 c) { return toneMapped(c * u_exposure); }

void main() {
#if SUPERSAMPLE == 1
  vec3 c = clamp(toneMap(texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb), 0.0, 1.0);
#else
  ivec2 base = ivec2(gl_FragCoord.xy) * SUPERSAMPLE;
  vec3 sum = vec3(0.0);
  for (int y = 0; y < SUPERSAMPLE; ++y)
    for (int x = 0; x < SUPERSAMPLE; ++x) sum += toneMap(texelFetch(u_hdr, base + ivec2(x, y), 0).rgb);
  vec3 c = clamp(sum / float(SUPERSAMPLE * SUPERSAMPLE), 0.0, 1.0);
#endif
  o_color = vec4(displayValue(c), 1.0);
}
