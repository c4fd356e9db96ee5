#version 450 core
// The sky behind everything: a gradient from horizon to zenith, a darker ground and
// a sun disk (common/sky.glsl, the tracers' text too); or, with SKY_IMAGE, a lat-long image (common/latlong.glsl) times an
// intensity, turned about +y; or, with SKY_ATMOSPHERE, the planet's air from the
// sky-view table (render/atmosphere_tables.h) and the sun's disk. All are linear
// radiance, as the ray tracer's environment (raytrace/environment.h) gives it.
in vec3 v_direction;
layout(location = 0) out vec4 o_color;

#if defined(SKY_ATMOSPHERE)
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"
uniform Atmosphere u_atmosphere;
layout(binding = UNIT_SKY_VIEW) uniform sampler2D u_skyView;
uniform vec3 u_up;           // the camera's zenith
uniform float u_altitude;    // the camera's, that the table was made for
uniform vec3 u_sunDirection;
// rgb: the disk's radiance at its centre, through the air, 0 for none (the
// environment cube leaves the sun to its light); w: the cosine of its radius.
uniform vec4 u_sunDisk;

// The cosine of the azimuth between d and the sun about the zenith (1 straight up,
// where the azimuth is moot).
float azimuthCosine(vec3 d, float mu, float muSun) {
  vec3 dh = d - mu * u_up, sh = u_sunDirection - muSun * u_up;
  float lengths = sqrt(dot(dh, dh) * dot(sh, sh));
  return lengths > 1e-12 ? clamp(dot(dh, sh) / lengths, -1.0, 1.0) : 1.0;
}

vec3 skyRadiance(vec3 d) {
  float mu = dot(d, u_up), muSun = dot(u_sunDirection, u_up);
  vec3 color = texture(u_skyView, skyViewUv(u_atmosphere, u_altitude, mu, azimuthCosine(d, mu, muSun))).rgb;
  float cosToSun = dot(d, u_sunDirection);
  if (cosToSun > u_sunDisk.w) {
    // Limb darkening at the fraction of the disk's radius (sines: the disk is small).
    float r = sqrt(max(1.0 - cosToSun * cosToSun, 0.0) / max(1.0 - u_sunDisk.w * u_sunDisk.w, 1e-12));
    color += u_sunDisk.rgb * sunLimbDarkening(min(r, 1.0));
  }
  return color;
}
#elif defined(SKY_IMAGE)
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
