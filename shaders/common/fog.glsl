// Exponential distance fog toward the sky colour.
vec3 applyFog(vec3 color, float distance, vec3 fogColor, float density) {
  float f = exp(-density * distance);
  return mix(fogColor, color, clamp(f, 0.0, 1.0));
}
