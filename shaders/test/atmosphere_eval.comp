#version 450 core
// tests/core/shading_texts_test.cpp: the atmosphere's layers (common/atmosphere.glsl)
// on the GPU's compiler, for random altitudes and scale heights, so that the C++
// build of the same text (core/atmosphere.h) can be compared case by case.
#include "common/atmosphere.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 heights;  // x: an altitude, y <= z: a range of them, w: a fraction of the sun's radius
  vec4 layers;   // Rayleigh's and Mie's scale heights, the ozone tent's centre and half width
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
struct Result {
  vec4 densities;
  vec4 extinction;
  vec4 bound;
  vec4 floorDensities;
  vec4 limb;
};
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  // Earth's coefficients (asset/scene_desc.h's AtmosphereDesc), the same literals as
  // the C++ side's.
  Atmosphere a;
  a.bottomRadius = 6360e3f;
  a.topRadius = 6460e3f;
  a.rayleighScattering = vec3(5.802e-6f, 13.558e-6f, 33.1e-6f);
  a.rayleighScaleHeight = c.layers.x;
  a.mieScattering = vec3(3.996e-6f);
  a.mieAbsorption = vec3(0.444e-6f);
  a.mieScaleHeight = c.layers.y;
  a.mieAnisotropy = 0.8f;
  a.ozoneAbsorption = vec3(0.650e-6f, 1.881e-6f, 0.085e-6f);
  a.ozoneCenter = c.layers.z;
  a.ozoneHalfWidth = c.layers.w;
  a.groundAlbedo = vec3(0.3f);
  Result r;
  vec3 d = atmosphereDensities(a, c.heights.x);
  r.densities = vec4(d, 0.0f);
  r.extinction = vec4(atmosphereExtinction(a, d), 0.0f);
  r.bound = vec4(atmosphereDensityBound(a, c.heights.y, c.heights.z), 0.0f);
  r.floorDensities = vec4(atmosphereDensityFloor(a, c.heights.y, c.heights.z), 0.0f);
  r.limb = vec4(sunLimbDarkening(c.heights.w), 0.0f);
  results[i] = r;
}
