// The display's curve, once for the post pass and for DIRECT_OUTPUT: a scene that
// needs no HDR target (scene_renderer.cpp's directOutput: no tone map, exposure 1,
// no MSAA, supersampling, sky, probes, blending or transmission) has its fragment
// shaders write display values into an RGBA8 target, and no post pass runs.
vec3 srgbEncoded(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// c: tone mapped and clamped to [0, 1].
vec3 displayValue(vec3 c) {
#ifdef OUTPUT_GAMMA22
  return pow(c, vec3(1.0 / 2.2));
#else
  return srgbEncoded(c);
#endif
}

// What a shaded fragment writes: linear radiance into the HDR target, or with
// DIRECT_OUTPUT its display value, opaque (as the post pass writes it).
vec4 targetColor(vec3 linear, float alpha) {
#ifdef DIRECT_OUTPUT
  return vec4(displayValue(clamp(linear, 0.0, 1.0)), 1.0);
#else
  return vec4(linear, alpha);
#endif
}
