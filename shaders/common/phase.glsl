// Phase functions of participating media, each with its sampling, written once: the
// path tracer's media and the rasterizer's in-scattering (issue #57) evaluate this
// text, and C++ compiles it with GLM (engine/core/phase.h).
// tests/raytrace/phase_test.cpp checks every sampler against its density with a
// chi-square test, and the densities' integrals and mean cosines by quadrature;
// tests/core/shading_texts_test.cpp runs the text on the GPU's compiler against the
// C++ build.
//
// In the subset of the two languages that common/sampling.glsl keeps to, after
// common/brdf.glsl (BRDF_INLINE, BRDF_PI). Angles are between the light's direction
// of travel before and after it scatters: cosTheta 1 is straight on. Sampled
// directions are local, the incoming direction of travel along +z; densities are per
// solid angle, and each phase function is its own density.

// Henyey and Greenstein's phase function of asymmetry g in (-1, 1): the mean cosine
// of the scattering angle is g (forward for g > 0, backward for g < 0, isotropic at 0).
// 1 - g^2 as (1 - g)(1 + g), and 1 + g^2 - 2 g cos as (1 - g)^2 + 2 g (1 - cos), or
// for g < 0 as (1 + g)^2 - 2 g (1 + cos): no difference of near numbers. For a
// strong g the textbook forms cancel (at g = 0.99 the peak kept three digits, and
// the density integrated to 1 + 1e-4).
BRDF_INLINE float phaseHenyeyGreenstein(float cosTheta, float g) {
  precise float denom = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * (1.0f - cosTheta)
                                  : (1.0f + g) * (1.0f + g) - 2.0f * g * (1.0f + cosTheta);
  precise float p = (1.0f - g) * (1.0f + g) / (4.0f * BRDF_PI * denom * sqrt(denom));
  return p;
}

// The cosine of an angle drawn from Henyey-Greenstein's density by inverting its CDF
// (pbrt-v4's form, turned to the direction of travel); uniform where |g| is too small
// for the inversion to be stable.
BRDF_INLINE float sampleHenyeyGreensteinCosine(float u, float g) {
  if (abs(g) < 1e-3f) return 1.0f - 2.0f * u;
  precise float g2 = g * g;
  precise float s = (1.0f - g2) / (1.0f + g - 2.0f * g * u);
  precise float cosTheta = (1.0f + g2 - s * s) / (2.0f * g);
  return clamp(cosTheta, -1.0f, 1.0f);
}

// Lord Rayleigh's phase function, 3 / (16 pi) (1 + cos^2): small particles, air.
BRDF_INLINE float phaseRayleigh(float cosTheta) {
  precise float p = 3.0f / (16.0f * BRDF_PI) * (1.0f + cosTheta * cosTheta);
  return p;
}

// The cosine drawn from Rayleigh's density: its CDF (mu^3 + 3 mu + 4) / 8 = u is a
// cubic with one real root, mu = w - 1 / w with w the cube root of a + sqrt(a^2 + 1),
// a = 4u - 2. Taken for |a| and its sign restored: for a < 0 the sum cancels.
BRDF_INLINE float sampleRayleighCosine(float u) {
  precise float a = 4.0f * u - 2.0f;
  precise float b = abs(a);
  precise float w = pow(b + sqrt(b * b + 1.0f), 1.0f / 3.0f);
  precise float mu = w - 1.0f / w;
  return clamp(a < 0.0f ? -mu : mu, -1.0f, 1.0f);
}

// A local direction at the drawn cosine from +z, its azimuth 2 pi u.
BRDF_INLINE vec3 directionAtCosine(float cosTheta, float u) {
  precise float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
  precise float phi = 2.0f * BRDF_PI * u;
  precise vec3 w = vec3(cos(phi) * sinTheta, sin(phi) * sinTheta, cosTheta);
  return w;
}

BRDF_INLINE vec3 samplePhaseHenyeyGreenstein(vec2 u, float g) {
  return directionAtCosine(sampleHenyeyGreensteinCosine(u.x, g), u.y);
}

BRDF_INLINE vec3 samplePhaseRayleigh(vec2 u) { return directionAtCosine(sampleRayleighCosine(u.x), u.y); }
