#version 450 core
// The sky's irradiance on the ground under the camera (1 x 1), per unit sun
// illuminance: pi times the mean radiance of 64 directions drawn by the cosine over
// the upper hemisphere (one per invocation). What the sky-view table lights the
// planet's ground with beside the sun; the ground is taken to see one sky to its
// horizon.
#include "common/brdf.glsl"
#include "common/phase.glsl"
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"
#include "atmosphere/march.glsl"

layout(local_size_x = 64) in;
layout(binding = IMAGE_SKY_TABLE, rgba32f) writeonly uniform image2D u_table;
uniform float u_muSun;  // the sun's zenith cosine

const int kSteps = 24;
shared vec3 s_radiance[64];

void main() {
  uint i = gl_LocalInvocationIndex;
  // Malley's method on an 8 x 8 stratified disk: uniform on the disk, cosine-weighted above it.
  float radius = sqrt((float(i % 8u) + 0.5) / 8.0), phi = 2.0 * ATMOSPHERE_PI * (float(i / 8u) + 0.5) / 8.0;
  float mu = sqrt(max(1.0 - radius * radius, 0.0));
  float sinSun = sqrt(max(1.0 - u_muSun * u_muSun, 0.0));
  AtmosphereRay ray = AtmosphereRay(0.0, mu, u_muSun, radius * cos(phi) * sinSun + mu * u_muSun);
  Scattering s = noScattering();
  scatterAlong(ray, 0.0, distanceToTop(u_atmosphere, 0.0, mu), kSteps, true, s);
  s_radiance[i] = s.radiance;
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (i < stride) s_radiance[i] += s_radiance[i + stride];
    barrier();
  }
  if (i == 0u) imageStore(u_table, ivec2(0), vec4(ATMOSPHERE_PI * s_radiance[0] / 64.0, 1.0));
}
