// The environment's one lat-long convention, written once: sky.frag includes this
// file, and C++ compiles the very same text with GLM (raytrace/environment.cpp), in
// the subset the two languages share (see common/brdf.glsl).
//
// u in [0, 1) turns about +y: u = 0.5 looks along +z, 0.75 along -x, 0 (and 1) along
// -z, 0.25 along +x. Seen from inside, looking along +z with +y up in the engine's
// right-handed frame, u grows to the right, so an image is not mirrored. v in [0, 1]:
// 0 at +y (the zenith, the image's top row), 0.5 at the horizon, 1 at -y. With
// phi = 2 pi (u - 0.5) and theta = pi v the direction is
// (-sin(theta) sin(phi), cos(theta), sin(theta) cos(phi)).

const float LATLONG_PI = 3.14159265358979f;

// The lat-long coordinates of direction `d` (any length but zero). Straight up or
// down, where u means nothing, u is 0.5 (GLSL leaves atan(0, 0) undefined).
vec2 latLongUv(vec3 d) {
  float horizontal = sqrt(d.x * d.x + d.z * d.z);
  float u = horizontal > 0.0f ? atan(-d.x, d.z) / (2.0f * LATLONG_PI) + 0.5f : 0.5f;
  // atan's +pi (u = 1) is the seam's other side: the same column as u = 0.
  return vec2(u >= 1.0f ? u - 1.0f : u, atan(horizontal, d.y) / LATLONG_PI);
}

// The unit direction at lat-long coordinates `uv`.
vec3 latLongDirection(vec2 uv) {
  float phi = 2.0f * LATLONG_PI * (uv.x - 0.5f);
  float theta = LATLONG_PI * uv.y;
  return vec3(-sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
}

// `d` turned about +y by the angle whose cosine and sine are `c` and `s`:
// counter-clockwise seen from above, +z toward +x.
vec3 rotateAboutY(vec3 d, float c, float s) {
  return vec3(c * d.x + s * d.z, d.y, c * d.z - s * d.x);
}
