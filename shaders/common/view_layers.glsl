// What layeredBrdf (common/brdf.glsl) takes of a hit's glTF layers that depends on
// the view, worked out once per hit for the Whitted tracers' lights and ambient and
// for the path tracers' Bsdf alike, written once: the GPU tracers include this file
// (rt/view_layers.glsl, which reads the material and the sheen's table), and C++
// compiles the very same text (engine/core/view_layers.h) for the CPU tracers
// (HitMaterial::atView, raytrace/rt_scene.h). In brdf.glsl's subset of the two
// languages, after it; rtDot, rtCross and mixAsGlm are glm's dot, cross and mix
// (rt/math.glsl on the GPU, glm's own in C++), and `precise` keeps the GPU from
// fusing what C++ rounds twice (common/sampling.glsl says more).

struct ViewLayers {
  float sheenAlbedo, sheenScale;  // the white sheen's albedo at N.V; what it leaves the base
  vec3 anisotropyT, anisotropyB;  // the stretch made orthogonal to n (unit), and n x it
  float anisotropy;               // 0 where there is no stretch to orient
  vec3 iridescenceF;              // the thin film's Fresnel at N.V
};

// For the unit shading normal n at N.V = nDotV: sheenAlbedo, the white sheen's
// albedo there (the caller's table lookup; 0 without a sheen); `stretch`, the
// anisotropy's direction in the world at the hit (zero where the hit has no uv
// gradient to orient it by, and then no stretch) and its strength; the film's
// share, index and thickness (nm) over the base's f0 (dielectricF0 and albedo mixed
// by metallic), whose Fresnel is taken at N.V no less than 1e-4.
BRDF_INLINE ViewLayers viewLayersOf(vec3 n, float nDotV, float sheenAlbedo, vec3 sheenColor, vec3 stretch,
                                    float anisotropy, float iridescence, float filmIor, float filmThickness,
                                    vec3 dielectricF0, vec3 albedo, float metallic) {
  ViewLayers v;
  v.sheenAlbedo = sheenAlbedo;
  v.sheenScale = sheenScaling(sheenColor, sheenAlbedo);
  v.anisotropyT = vec3(0.0f);
  v.anisotropy = 0.0f;
  if (anisotropy > 0.0f) {
    precise vec3 t = stretch - n * rtDot(n, stretch);
    float len = sqrt(rtDot(t, t));
    if (len > 1e-6f) {
      v.anisotropyT = t / len;
      v.anisotropy = anisotropy;
    }
  }
  v.anisotropyB = rtCross(n, v.anisotropyT);
  v.iridescenceF = vec3(0.0f);
  if (iridescence > 0.0f) {
    v.iridescenceF = iridescenceFresnel(1.0f, filmIor, max(nDotV, 1e-4f), filmThickness,
                                        mixAsGlm(dielectricF0, albedo, metallic));
  }
  return v;
}
