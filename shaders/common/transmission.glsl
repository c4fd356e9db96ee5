// KHR_materials_transmission and KHR_materials_volume in the rasterizer, as the
// Khronos Sample Viewer draws them: what lies behind a transmissive surface is the
// opaque pass's image (render/scene_renderer.cpp copies it, mipmapped, before the
// transmissive draws), read where the refracted ray leaves the volume, blurred by
// the surface's roughness through the mip chain, absorbed along the way
// (Beer-Lambert) and weighted by common/brdf.glsl's transmittedShare. Thin walls
// (thickness 0) show what lies straight behind them. Shortcuts, measured against the
// path tracer's exact refraction: one refraction only (the exit is not bent back),
// no transmissive surface sees another, and what is off screen is the image's edge.
layout(binding = UNIT_TRANSMISSION_SOURCE) uniform sampler2D u_transmissionSource;
uniform mat4 u_model;  // the mesh's world matrix (its scale turns the thickness into metres)
uniform float u_ior;
uniform float u_attenuationDistance;  // 0: nothing absorbed
uniform vec3 u_attenuationColor;

// The light that comes through the surface toward the eye.
vec3 transmittedLight(Surface s) {
  if (g_transmission <= 0.0) return vec3(0.0);
  float ior = max(u_ior, 1.0);  // glTF's ior 0 (a mirror) bends nothing
  vec3 scale = vec3(length(u_model[0].xyz), length(u_model[1].xyz), length(u_model[2].xyz));
  vec3 ray = normalize(refract(-s.toEye, s.n, 1.0 / ior)) * g_thickness * scale;
  vec4 clip = u_viewProjection * vec4(s.position + ray, 1.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  float levels = log2(float(textureSize(u_transmissionSource, 0).x));
  vec3 behind = textureLod(u_transmissionSource, uv, levels * transmissionRoughness(s.roughness, ior)).rgb;
  behind *= volumeAttenuation(u_attenuationColor, u_attenuationDistance, length(ray));
  // What the surface reflects toward the eye does not come through.
  float nDotV = max(dot(s.n, s.toEye), 1e-4);
#if defined(AMBIENT_SH) || defined(AMBIENT_IBL)
  vec3 table = texture(u_splitSum, vec2(nDotV, s.roughness)).rgb;
  vec3 reflected = g_dielectricF0 * table.x + vec3(g_dielectricF90 * table.y);
#else
  vec3 reflected = schlickFresnel90(g_dielectricF0, g_dielectricF90, nDotV);
#endif
  // A sheen lies over what comes through as over the base (no sheen: a factor of 1).
  return transmittedShare(s.albedo, s.metallic, g_transmission, reflected) * behind * g_sheenScale;
}
