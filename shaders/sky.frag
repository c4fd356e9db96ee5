#version 450 core
// The sky behind everything: a gradient from horizon to zenith, a darker ground and
// a sun disk (common/sky.glsl, the tracers' text too); or, with SKY_IMAGE, a lat-long image (common/latlong.glsl) times an
// intensity, turned about +y. Both are linear radiance, as the ray tracer's
// environment (raytrace/environment.h) gives it.
in vec3 v_direction;
layout(location = 0) out vec4 o_color;

#ifdef SKY_IMAGE
#include "common/latlong.glsl"
// Linear RGB (float), repeating in u, clamped in v, mipmapped.
layout(binding = UNIT_SKY_IMAGE) uniform sampler2D u_skyImage;
uniform float u_skyIntensity;
uniform vec2 u_skyRotation;  // cosine and sine of the image's turn about +y

vec3 skyRadiance(vec3 d) {
  vec2 uv = latLongUv(rotateAboutY(d, u_skyRotation.x, -u_skyRotation.y));
  // u jumps from 1 to 0 across the seam, and derivatives taken there would pick the
  // smallest mip level: a line of wrong texels down the sky. A u that wraps on the
  // opposite side is continuous there; each derivative takes the smaller of the two
  // (Tarini 2012, "Cylindrical and toroidal parameterizations without vertex seams").
  float uOpposite = fract(uv.x + 0.5);
  vec2 dx = vec2(dFdx(uv.x), dFdx(uv.y)), dy = vec2(dFdy(uv.x), dFdy(uv.y));
  float dxOpposite = dFdx(uOpposite), dyOpposite = dFdy(uOpposite);
  if (abs(dxOpposite) < abs(dx.x)) dx.x = dxOpposite;
  if (abs(dyOpposite) < abs(dy.x)) dy.x = dyOpposite;
  return textureGrad(u_skyImage, uv, dx, dy).rgb * u_skyIntensity;
}
#else
#include "common/sky.glsl"
uniform vec3 u_sunDirection;
uniform vec3 u_skyColor;
uniform vec3 u_horizonColor;
uniform vec3 u_groundColor;
uniform float u_sunDisk;  // 1: draw the disk; 0: the scene has no sun or asked for none

vec3 skyRadiance(vec3 d) {
  return gradientSky(d, u_horizonColor, u_skyColor, u_groundColor, dot(d, u_sunDirection), u_sunDisk);
}
#endif

#ifdef DIRECT_OUTPUT
#include "common/output.glsl"
#endif

void main() {
  vec3 color = skyRadiance(normalize(v_direction));
#if defined(DIRECT_OUTPUT)
  o_color = targetColor(color, 1.0);  // the view's display value (common/output.glsl)
#elif defined(HDR_OUTPUT)
  o_color = vec4(color, 1.0);  // the post pass applies exposure and tone map
#else
  o_color = vec4(color / (1.0 + color), 1.0);
#endif
}
