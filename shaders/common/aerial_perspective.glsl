// A planet's air between the camera and an opaque surface (Hillaire 2020's aerial
// perspective): the surface's radiance L seen as L T + in-scattered, both read from
// the aerial-perspective volume (render/atmosphere_tables.h) at the surface's froxel.
// After common/frame.glsl; positions camera-relative. The volume is the main view's:
// a reflection probe's view reads it at its own screen position, near enough for the
// few metres of air a probe sees.
#include "common/atmosphere.glsl"
#include "atmosphere/lut.glsl"

layout(binding = UNIT_AERIAL_PERSPECTIVE) uniform sampler3D u_aerialPerspective;

vec3 applyAerialPerspective(vec3 color, vec3 position) {
  vec4 clip = u_viewProjection * vec4(position, 1.0);
  vec2 uv = clip.xy / max(clip.w, 1e-6) * 0.5 + 0.5;
  // The slices' texel centres are at the square of their depth (aerialSliceDistance).
  float w = sqrt(length(position) / AERIAL_DEPTH);
  float z = clamp(w, 0.5 / AERIAL_SIZE, 1.0 - 0.5 / AERIAL_SIZE) * 0.5;
  // Nearer than the first slice's centre the air fades to none.
  float fade = min(w * AERIAL_SIZE * 2.0, 1.0);
  vec3 inscattered = texture(u_aerialPerspective, vec3(uv, z)).rgb * fade;
  vec3 transmittance = mix(vec3(1.0), texture(u_aerialPerspective, vec3(uv, z + 0.5)).rgb, fade);
  return color * transmittance + inscattered;
}
