#version 450 core
// tests/render/display_output_test.cpp: common/output.glsl's display curves as a frame
// stores them, one value a pixel (row-major from the bottom row), to compare with
// core/srgb_curve.h's exact bytes: under DIRECT_OUTPUT (TONE_MAP 2, EXPOSURE 1) a
// direct-output fragment's ACES and sRGB, else the post pass's sRGB curve.
#include "common/output.glsl"

layout(std430, binding = 0) readonly buffer Values { float values[]; };
uniform int u_width;

layout(location = 0) out vec4 o_color;

void main() {
  float v = values[int(gl_FragCoord.y) * u_width + int(gl_FragCoord.x)];
#ifdef DIRECT_OUTPUT
  o_color = targetColor(vec3(v), 1.0);
#else
  o_color = vec4(displayValue(vec3(v)), 1.0);
#endif
}
