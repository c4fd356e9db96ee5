// The gradient sky, written once: the rasterizer's sky (sky.frag, and through it the
// environment cube its ambient light is made from), the GPU tracers' environment
// (rt/sky.glsl) and the CPU tracers' (raytrace/environment.cpp, through its C++
// compile engine/core/sky.h) draw it with this text. tests/core/shading_texts_test.cpp
// compares the GLSL compile with the C++ one.
//
// In the subset of the two languages that common/brdf.glsl keeps to. The cosine
// toward the sun comes from the caller, rounded as its other dot products are
// (GLSL's dot in the rasterizer, rt/math.glsl's rtDot in the GPU tracers, glm's on
// the CPU); mix and smoothstep are GLSL's on the GPU and glm's in C++. The root is
// pow(x, 0.5): the rasterizer's goldens were made with what its compiler makes of
// that, and C++ takes it as std::sqrt, the exact root, as the CPU always has
// (core/sky.h).
#ifndef BRDF_INLINE
#define BRDF_INLINE
#endif

// For the unit direction d: from the horizon to the zenith, or to the ground below
// it, by the square root of the elevation's sine; and a sun disk of sunDisk times
// (4, 3.6, 3), fading in between cosines 0.9995 and 0.9998 toward the sun. sunDisk is
// 1 where the disk is drawn and 0 where not (the path tracers sample the sun as a
// light; the environment cube leaves it to the sun's own light): a factor, not a
// branch, so that the rasterizer's one program draws both.
BRDF_INLINE vec3 gradientSky(vec3 d, vec3 horizon, vec3 zenith, vec3 ground, float cosToSun, float sunDisk) {
  vec3 color = d.y >= 0.0f ? mix(horizon, zenith, pow(d.y, 0.5f)) : mix(horizon, ground, pow(-d.y, 0.5f));
  float sun = smoothstep(0.9995f, 0.9998f, cosToSun);
  return color + vec3(4.0f, 3.6f, 3.0f) * (sun * sunDisk);
}
