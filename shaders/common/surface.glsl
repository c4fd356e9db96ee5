// The deferred characters' surface (SceneRenderer's deferred characters): what
// scene.frag's shading reads of a fragment, left by the surface pass (SURFACE_OUT)
// where the fragment is nearest, and read back by one full-screen pass (SURFACE_IN,
// vertices from sky.vert) that shades each pixel once. One RGBA32UI texel: uv and
// the base colour's level of detail as the floats' bits (what a forward draw
// would sample with), the shading normal octahedral in two 16-bit snorms (within
// 5e-5 of its direction). With SURFACE_POSITION the distance from the eye too
// (R32F), for what lighting reads of the position (shadows, point lights, fog).

// The unit sphere onto the square [-1, 1]^2: the upper half as the diamond inside,
// the lower half folded over its edges.
vec2 octahedralEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 signs = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * signs;
}

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  vec2 signs = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signs;
  return normalize(n);
}

#ifdef SURFACE_OUT
layout(location = 0) out uvec4 o_surface;
#ifdef SURFACE_POSITION
layout(location = 1) out float o_surfaceDistance;
#endif

// `n` the shading normal (unit, the lit side's); `position` camera-relative.
void writeSurface(vec3 position, vec3 n, vec2 uv) {
  float lod = 0.0;
#ifdef TEXTURED
  // The level texture() would take here, from this triangle's derivatives.
  lod = textureQueryLod(u_baseColorTexture, materialUv(SLOT_BASE_COLOR, uv)).y;
#endif
  o_surface = uvec4(floatBitsToUint(uv), packSnorm2x16(octahedralEncode(n)), floatBitsToUint(lod));
#ifdef SURFACE_POSITION
  o_surfaceDistance = length(position);
#endif
}
#endif

#ifdef SURFACE_IN
in vec3 v_direction;  // sky.vert's: camera-relative, through the pixel's centre
layout(binding = UNIT_CHARACTER_SURFACE) uniform usampler2D u_surface;
#ifdef SURFACE_POSITION
layout(binding = UNIT_CHARACTER_DISTANCE) uniform sampler2D u_surfaceDistance;
#endif

// What a forward draw interpolates, read from the surface at this pixel instead.
vec3 v_position;
vec3 v_normal;
vec2 v_uv;

void readSurface() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uvec4 surface = texelFetch(u_surface, pixel, 0);
  v_uv = uintBitsToFloat(surface.xy);
  v_normal = octahedralDecode(unpackSnorm2x16(surface.z));
  g_baseColorLod = uintBitsToFloat(surface.w);
#ifdef SURFACE_POSITION
  v_position = normalize(v_direction) * texelFetch(u_surfaceDistance, pixel, 0).x;
#else
  v_position = normalize(v_direction);  // lighting reads its direction only
#endif
}
#endif
