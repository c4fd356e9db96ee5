#version 450 core
// The transmittance table (256 x 64): from each texel's altitude along its mu to the
// top of the air, exp of minus the optical depth of common/atmosphere.glsl's layers.
// 64 midpoint steps spaced by the square (short where the air is densest); the
// ground is not in the way here, sunTransmittance asks it apart.
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IMAGE_SKY_TABLE, rgba32f) writeonly uniform image2D u_table;
uniform Atmosphere u_atmosphere;

const int kSteps = 64;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(TRANSMITTANCE_SIZE)))) return;
  vec2 ray = transmittanceTexelRay(u_atmosphere, (vec2(texel) + 0.5) / TRANSMITTANCE_SIZE);
  AtmosphereRay r = AtmosphereRay(ray.x, ray.y, 0.0, 0.0);
  float rayLength = distanceToTop(u_atmosphere, ray.x, ray.y);
  vec3 depth = vec3(0.0);
  float previous = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    float x = float(i + 1) / float(kSteps), xMid = (float(i) + 0.5) / float(kSteps);
    float next = rayLength * x * x;
    float altitude = atmosphereRayAt(u_atmosphere, r, rayLength * xMid * xMid).x;
    depth += atmosphereExtinction(u_atmosphere, atmosphereDensities(u_atmosphere, altitude)) * (next - previous);
    previous = next;
  }
  imageStore(u_table, texel, vec4(exp(-depth), 1.0));
}
