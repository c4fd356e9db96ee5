#version 450 core
// The aerial-perspective volume (32 x 32 x 32 froxels over the view; Hillaire 2020,
// section 5.4): for each froxel column, one ray from the camera marched slice by
// slice (atmosphere/lut.glsl's aerialSliceDistance), storing at each slice what the
// air between it and the camera scatters toward the camera (times the sun's
// illuminance) in z 0-31, and its transmittance in z 32-63. A surface at that
// distance is seen as L T + inscattered.
#include "common/brdf.glsl"
#include "common/phase.glsl"
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"
#include "atmosphere/march.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IMAGE_SKY_TABLE, rgba16f) writeonly uniform image3D u_volume;
uniform mat4 u_inverseViewProjection;  // camera-relative
uniform vec3 u_up;                     // the camera's zenith
uniform vec3 u_sunDirection;           // toward the sun
uniform float u_altitude;              // the camera's
uniform vec3 u_sunIlluminance;

const int kStepsPerSlice = 2;

void main() {
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(column, ivec2(AERIAL_SIZE)))) return;
  vec2 ndc = (vec2(column) + 0.5) / AERIAL_SIZE * 2.0 - 1.0;
  vec4 far = u_inverseViewProjection * vec4(ndc, 0.5, 1.0);
  vec3 d = normalize(far.xyz / far.w);
  AtmosphereRay ray = AtmosphereRay(u_altitude, dot(d, u_up), dot(u_sunDirection, u_up), dot(d, u_sunDirection));
  float end = atmosphereRayEnd(ray).x;
  Scattering s = noScattering();
  float previous = 0.0;
  for (int slice = 0; slice < int(AERIAL_SIZE); ++slice) {
    float t = min(aerialSliceDistance(float(slice) + 0.5), end);
    scatterAlong(ray, previous, t, kStepsPerSlice, false, s);
    previous = t;
    imageStore(u_volume, ivec3(column, slice), vec4(s.radiance * u_sunIlluminance, 1.0));
    imageStore(u_volume, ivec3(column, slice + int(AERIAL_SIZE)), vec4(s.transmittance, 1.0));
  }
}
