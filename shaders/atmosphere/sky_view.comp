#version 450 core
// The sky-view table (192 x 108; Hillaire 2020, section 5.3): the radiance the
// camera's altitude sees in each texel's direction (atmosphere/lut.glsl's
// skyViewUv), scattered along the ray to the top of the air or to the ground, and
// there the ground's own, times the sun's illuminance.
#include "common/brdf.glsl"
#include "common/phase.glsl"
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"
#include "atmosphere/march.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IMAGE_SKY_TABLE, rgba32f) writeonly uniform image2D u_table;
layout(binding = UNIT_SKY_GROUND_IRRADIANCE) uniform sampler2D u_groundIrradiance;
uniform float u_altitude;          // the camera's
uniform float u_muSun;             // the sun's zenith cosine there
uniform vec3 u_sunIlluminance;     // pi times the sun light's colour and intensity

const int kSteps = 32;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(SKY_VIEW_SIZE)))) return;
  vec2 direction = skyViewTexelDirection(u_atmosphere, u_altitude, (vec2(texel) + 0.5) / SKY_VIEW_SIZE);
  float mu = direction.x, sinTheta = sqrt(max(1.0 - mu * mu, 0.0));
  float sinSun = sqrt(max(1.0 - u_muSun * u_muSun, 0.0));
  AtmosphereRay ray = AtmosphereRay(u_altitude, mu, u_muSun, sinTheta * direction.y * sinSun + mu * u_muSun);
  vec2 end = atmosphereRayEnd(ray);
  Scattering s = noScattering();
  scatterAlong(ray, 0.0, end.x, kSteps, true, s);
  vec3 radiance = s.radiance;
  if (end.y > 0.0) radiance += groundRadiance(ray, end.x, texelFetch(u_groundIrradiance, ivec2(0), 0).rgb, s);
  imageStore(u_table, texel, vec4(radiance * u_sunIlluminance, 1.0));
}
