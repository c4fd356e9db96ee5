// Environment::radiance for the background colour and the gradient sky (image skies
// are refused before a kernel runs), shared by the GPU integrators. After
// rt/surface.glsl (rtNormalize).

// 0 the background colour, 1 the gradient sky.
uniform int u_skyKind;
uniform vec3 u_background, u_zenith, u_horizon, u_ground;
uniform int u_sunDisk;  // the gradient draws a disk toward u_sun
uniform vec3 u_sun;

// `sunDisk` false leaves the disk out (the path tracer samples the sun as a light).
vec3 rtSky(vec3 dir, bool sunDisk) {
  if (u_skyKind == 0) return u_background;
  vec3 d = rtNormalize(dir);
  vec3 color = d.y >= 0.0 ? mix(u_horizon, u_zenith, sqrt(d.y)) : mix(u_horizon, u_ground, sqrt(-d.y));
  if (sunDisk && u_sunDisk != 0) {
    float c = rtDot(d, u_sun);
    float s = clamp((c - 0.9995) / (0.9998 - 0.9995), 0.0, 1.0);
    color += vec3(4.0, 3.6, 3.0) * (s * s * (3.0 - 2.0 * s));
  }
  return color;
}
