// A spot light's cone (glTF's KHR_lights_punctual), written once: the rasterizer's
// light loop (common/direct_light.glsl), the GPU tracers (rt/pathtrace.comp,
// rt/whitted.comp) and the CPU tracers (through its C++ compile engine/core/spot_cone.h)
// weigh a spot's light with this text. tests/core/shading_texts_test.cpp compares the
// GLSL compile with the C++ one.
//
// In the subset of the two languages that common/brdf.glsl keeps to.
#ifndef BRDF_INLINE
#define BRDF_INLINE
#endif

// The share of a spot's light that leaves it toward a point, as the Khronos Sample
// Viewer draws it: all of it inside the inner cone, none outside the outer one, and
// between them the square of the linear ramp in the cosine. `cosAngle`: the cosine
// between the unit direction from the point toward the light and the spot's axis
// turned toward the light (scene/environment.h's LightCone); `cosOuter`, `cosInner`:
// the cosines of the cones' half-angles. A point light is a spot whose cones hold
// every direction (cosines below -1), for which the share is exactly 1. Where the
// two cones are one, the edge is sharp: no division by their difference.
BRDF_INLINE float spotAttenuation(float cosAngle, float cosOuter, float cosInner) {
  if (!(cosAngle > cosOuter)) return 0.0f;
  if (cosAngle >= cosInner) return 1.0f;
  float t = (cosAngle - cosOuter) / (cosInner - cosOuter);
  return t * t;
}
