#version 450 core
// The multiple-scattering table (32 x 32; Hillaire 2020, section 5.5): at each
// texel's altitude and sun, the second order of scattering L2 and the fraction f_ms
// of light scattered again, each averaged over 64 directions of the sphere (one per
// invocation), isotropic; every order from the second is L2 / (1 - f_ms) (eq. 9),
// which the other tables scatter once more by sigma_s.
#define MULTI_SCATTERING_PASS 1
#include "common/brdf.glsl"
#include "common/phase.glsl"
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"
#include "atmosphere/march.glsl"

layout(local_size_x = 64) in;
layout(binding = IMAGE_SKY_TABLE, rgba32f) writeonly uniform image2D u_table;

const int kSteps = 20;
shared vec3 s_radiance[64];
shared vec3 s_fraction[64];

void main() {
  ivec2 texel = ivec2(gl_WorkGroupID.xy);
  vec2 uv = (vec2(texel) + 0.5) / MULTI_SCATTERING_SIZE;
  float muSun = texelCentresToUnit(uv.x, MULTI_SCATTERING_SIZE) * 2.0 - 1.0;
  float altitude = texelCentresToUnit(uv.y, MULTI_SCATTERING_SIZE) * atmosphereThickness(u_atmosphere);
  // An 8 x 8 grid even in azimuth and in the zenith's cosine: even over the sphere.
  uint i = gl_LocalInvocationIndex;
  float phi = 2.0 * ATMOSPHERE_PI * (float(i % 8u) + 0.5) / 8.0;
  float mu = 1.0 - 2.0 * (float(i / 8u) + 0.5) / 8.0;
  float sinTheta = sqrt(max(1.0 - mu * mu, 0.0)), sinSun = sqrt(max(1.0 - muSun * muSun, 0.0));
  AtmosphereRay ray = AtmosphereRay(altitude, mu, muSun, sinTheta * cos(phi) * sinSun + mu * muSun);
  vec2 end = atmosphereRayEnd(ray);
  Scattering s = noScattering();
  scatterAlong(ray, 0.0, end.x, kSteps, false, s);
  // The ground lit by the sun alone (the paper's), as the higher orders see it.
  if (end.y > 0.0) {
    s.radiance += groundRadiance(ray, end.x, vec3(0.0), s);
    // Beyond the paper: the ground returns light to the field too. Under the unit
    // isotropic field f_ms assumes, a Lambertian ground reflects radiance albedo
    // (irradiance pi over pi): the series then counts the orders that bounce off the
    // ground, which the path tracer has. On sky.json it brought the zenith's blue at
    // 30 degrees from 83 % of the path tracer's to 89 %.
    s.multiScatteringAs1 += s.transmittance * u_atmosphere.groundAlbedo;
  }
  s_radiance[i] = s.radiance;
  s_fraction[i] = s.multiScatteringAs1;
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (i < stride) {
      s_radiance[i] += s_radiance[i + stride];
      s_fraction[i] += s_fraction[i + stride];
    }
    barrier();
  }
  if (i == 0u) {
    // The sphere's mean of L2 and of f_ms (isotropic: the phase's 1 / 4 pi times 4 pi).
    vec3 second = s_radiance[0] / 64.0, fraction = s_fraction[0] / 64.0;
    imageStore(u_table, texel, vec4(second / (1.0 - fraction), 1.0));
  }
}
