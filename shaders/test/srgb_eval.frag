#version 450 core
// tests/gl/srgb_curve_test.cpp: common/output.glsl's sRGB curve as a frame stores it,
// one linear value a pixel (row-major from the bottom row), to compare with
// core/srgb_curve.h's exact bytes.
#include "common/output.glsl"

layout(std430, binding = 0) readonly buffer Values { float values[]; };
uniform int u_width;

layout(location = 0) out vec4 o_color;

void main() {
  float v = values[int(gl_FragCoord.y) * u_width + int(gl_FragCoord.x)];
  o_color = vec4(srgbEncoded(vec3(v)), 1.0);
}
