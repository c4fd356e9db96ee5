// What image-based lighting shares between its C++ half (the BRDF table and the SH
// projection, engine/core/ibl_tables.cpp) and its GLSL half (the prefilter,
// shaders/ibl_prefilter.comp, and the ambient of common/shading.glsl), in the
// subset of the two languages that common/brdf.glsl keeps to. Include brdf.glsl
// first: the GGX sampled here is its ggxDistribution, at its ggxAlpha.

// Point i of n of the Hammersley set: i / n and the radical inverse of i in base 2.
// Low discrepancy, so a few dozen samples of a lobe integrate it without visible
// noise, and the same points every time: the tables are deterministic.
BRDF_INLINE vec2 hammersley(uint i, uint n) {
  uint bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return vec2(float(i) / float(n), float(bits) * 2.3283064365386963e-10f);
}

// A half vector about unit normal n drawn with density ggxDistribution(n, h, alpha)
// * N.H (Walter et al. 2007, eq. 35-36): cos^2 theta = (1 - u) / (1 + (alpha^2 - 1) u).
BRDF_INLINE vec3 ggxSampleHalfVector(vec2 u, float alpha, vec3 n) {
  float a2 = alpha * alpha;
  float cosTheta = sqrt(max((1.0f - u.y) / (1.0f + (a2 - 1.0f) * u.y), 0.0f));
  float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
  float phi = 2.0f * BRDF_PI * u.x;
  vec3 up = abs(n.z) < 0.999f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f);
  vec3 tx = normalize(cross(up, n));
  vec3 ty = cross(n, tx);
  return normalize(tx * (sinTheta * cos(phi)) + ty * (sinTheta * sin(phi)) + n * cosTheta);
}

// The unit direction through point (s, t) in [0, 1]^2 of GL cube face `face` (+x,
// -x, +y, -y, +z, -z), as GL's cube lookup maps directions to faces (GL 4.5 spec,
// table 8.19): t = 0 is the face's first row.
BRDF_INLINE vec3 cubeFaceDirection(int face, float s, float t) {
  float sc = 2.0f * s - 1.0f;
  float tc = 2.0f * t - 1.0f;
  vec3 d = vec3(sc, -tc, 1.0f);                       // +z
  if (face == 0) d = vec3(1.0f, -tc, -sc);
  if (face == 1) d = vec3(-1.0f, -tc, sc);
  if (face == 2) d = vec3(sc, 1.0f, tc);
  if (face == 3) d = vec3(sc, -1.0f, -tc);
  if (face == 5) d = vec3(-sc, -tc, -1.0f);
  return normalize(d);
}

// The real spherical harmonics of order 2 (bands 0 to 2), basis function i in
// Ramamoorthi and Hanrahan's order (2001, eq. 3): Y00; Y1-1, Y10, Y11; Y2-2, Y2-1,
// Y20, Y21, Y22, at unit direction d.
BRDF_INLINE float shBasis(int i, vec3 d) {
  if (i == 0) return 0.282095f;
  if (i == 1) return 0.488603f * d.y;
  if (i == 2) return 0.488603f * d.z;
  if (i == 3) return 0.488603f * d.x;
  if (i == 4) return 1.092548f * d.x * d.y;
  if (i == 5) return 1.092548f * d.y * d.z;
  if (i == 6) return 0.315392f * (3.0f * d.z * d.z - 1.0f);
  if (i == 7) return 1.092548f * d.x * d.z;
  return 0.546274f * (d.x * d.x - d.y * d.y);
}

// The clamped cosine's convolution weight of band l (ibid., eq. 8): irradiance
// E = sum over l, m of shBandWeight(l) L_lm Y_lm.
BRDF_INLINE float shBandWeight(int i) {
  if (i == 0) return BRDF_PI;
  if (i < 4) return 2.0f * BRDF_PI / 3.0f;
  return BRDF_PI / 4.0f;
}
