// The display's end of the pipeline, once for the post pass and for DIRECT_OUTPUT:
// exposure, the tone map and the output curve. A scene that needs no HDR target
// (scene_renderer_setup.cpp's needsNoHdrTarget: no MSAA, supersampling, probes,
// blending or transmission) has its fragment shaders apply them and write display
// values into an RGBA8 target, and no post pass runs. Variants: TONE_MAP 0 none
// (clamp) / 1 Reinhard / 2 ACES (Narkowicz fit); OUTPUT_GAMMA22 (the course's 1/2.2;
// else sRGB); with DIRECT_OUTPUT, EXPOSURE (the post pass takes it as a uniform).
#ifndef TONE_MAP
#define TONE_MAP 2
#endif

// c: linear radiance times the exposure.
vec3 toneMapped(vec3 c) {
#if TONE_MAP == 1
  return c / (1.0 + c);
#elif TONE_MAP == 2
  return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
#else
  return clamp(c, 0.0, 1.0);
#endif
}

#ifndef OUTPUT_GAMMA22
// The curves by core/srgb_curve.h's tables (the renderer binds the one its programs
// read): a bin's byte, plus one from its threshold on. The exact curves' bytes,
// where pow() cost two polynomials a channel on llvmpipe and was not exact.
layout(binding = UNIT_DISPLAY_TABLE) uniform samplerBuffer u_displayTable;

// v >= 0 by a table over [0, domain): its display value, a byte over 255.
float tableByte(float v, float domain) {
  int bins = textureSize(u_displayTable);
  float x = min(v, domain);
  vec2 bin = texelFetch(u_displayTable, clamp(int(x * (float(bins) / domain)), 0, bins - 1)).xy;
  return (bin.x + (x >= bin.y ? 1.0 : 0.0)) / 255.0;
}

// c in [0, 1], by srgbTable().
vec3 srgbEncoded(vec3 c) { return vec3(tableByte(c.r, 1.0), tableByte(c.g, 1.0), tableByte(c.b, 1.0)); }
#endif

// c: tone mapped and clamped to [0, 1].
vec3 displayValue(vec3 c) {
#ifdef OUTPUT_GAMMA22
  return pow(c, vec3(1.0 / 2.2));
#else
  return srgbEncoded(c);
#endif
}

// What a shaded fragment writes: linear radiance into the HDR target, or with
// DIRECT_OUTPUT its display value, opaque (as the post pass writes it: the same
// curve on the radiance before the HDR target's rounding to half floats). After
// ACES, the tone map and the sRGB curve are one table, acesSrgbTable(): one fetch a
// channel, and the exact bytes of both.
vec4 targetColor(vec3 linear, float alpha) {
#if defined(DIRECT_OUTPUT) && TONE_MAP == 2 && !defined(OUTPUT_GAMMA22)
  vec3 x = max(linear * float(EXPOSURE), vec3(0.0));
  return vec4(tableByte(x.r, 8.0), tableByte(x.g, 8.0), tableByte(x.b, 8.0), 1.0);
#elif defined(DIRECT_OUTPUT)
  return vec4(displayValue(clamp(toneMapped(linear * float(EXPOSURE)), 0.0, 1.0)), 1.0);
#else
  return vec4(linear, alpha);
#endif
}
