// Environment::radiance, shared by the GPU integrators: the background colour, the
// gradient sky (common/sky.glsl, the CPU's and the rasterizer's text), or a lat-long image (its linear RGB as Environment holds it, sampled
// as Environment::bilinear does: wrapped around, clamped at the poles) times its
// intensity, turned about +y. After rt/math.glsl.
#include "common/latlong.glsl"
#include "common/sky.glsl"

// 0 the background colour, 1 the gradient sky (an image: RT_SKY_IMAGE).
uniform int u_skyKind;
uniform vec3 u_background, u_zenith, u_horizon, u_ground;
uniform int u_sunDisk;  // the gradient draws a disk toward u_sun
uniform vec3 u_sun;

// The image, built with RT_SKY_IMAGE.
#ifdef RT_SKY_IMAGE
uniform ivec2 u_skyImageSize;
uniform float u_skyIntensity;
uniform vec2 u_skyRotation;  // the image's turn: cosine, sine
layout(std430, binding = BUFFER_RT_SKY_IMAGE) readonly buffer RtSkyImage { float rtSkyImage[]; };

vec3 rtSkyTexel(int x, int y) {
  int i = 3 * (y * u_skyImageSize.x + x);
  return vec3(rtSkyImage[i], rtSkyImage[i + 1], rtSkyImage[i + 2]);
}

vec3 rtSkyImageAt(vec2 uv) {
  int w = u_skyImageSize.x, h = u_skyImageSize.y;
  precise float x = uv.x * float(w) - 0.5, y = uv.y * float(h) - 0.5;
  float x0f = floor(x), y0f = floor(y);
  precise float fx = x - x0f, fy = y - y0f;
  int x0 = wrapMod(int(x0f), w), x1 = wrapMod(int(x0f) + 1, w);
  int y0 = clamp(int(y0f), 0, h - 1), y1 = clamp(int(y0f) + 1, 0, h - 1);
  vec3 top = mixAsGlm(rtSkyTexel(x0, y0), rtSkyTexel(x1, y0), fx);
  vec3 bottom = mixAsGlm(rtSkyTexel(x0, y1), rtSkyTexel(x1, y1), fx);
  return mixAsGlm(top, bottom, fy);
}
#endif

// `sunDisk` false leaves the disk out (the path tracer samples the sun as a light).
vec3 rtSky(vec3 dir, bool sunDisk) {
  if (u_skyKind == 0) return u_background;
#ifdef RT_SKY_IMAGE
  // The image turned by the rotation shows at `dir` what it holds at `dir` turned back.
  vec3 local = rotateAboutY(dir, u_skyRotation.x, -u_skyRotation.y);
  precise vec3 radiance = rtSkyImageAt(latLongUv(local)) * u_skyIntensity;
  return radiance;
#endif
  vec3 d = rtNormalize(dir);
  return gradientSky(d, u_horizon, u_zenith, u_ground, rtDot(d, u_sun), sunDisk && u_sunDisk != 0 ? 1.0 : 0.0);
}
