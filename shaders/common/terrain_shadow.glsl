// Shadow hook for terrain.frag: the sun's visibility (0..1) at a camera-relative
// position. A stub returning 1 until shadows are wired for terrain; defining SHADOWS
// is where a real lookup (common/shadows.glsl's sunShadow) goes.
#ifdef SHADOWS
// TODO(lead): return sunShadow(position, normal) once terrain receives the Frame block.
float shadowFactor(vec3 position) { return 1.0; }
#else
float shadowFactor(vec3 position) { return 1.0; }
#endif
