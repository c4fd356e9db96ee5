// The path tracers' sampling routines, each with the density it draws from, written
// once: the GPU path tracer includes this file (rt/pathtrace.comp), and C++ compiles
// the very same text with GLM (engine/core/sampling.h) for the CPU path tracer
// (raytrace/sampling.h, common/bsdf.glsl) and the split-sum table (core/ibl_tables.cpp).
// tests/raytrace/sampling_test.cpp checks every sampler against its pdf with a
// chi-square test; tests/core/shading_texts_test.cpp runs this text on the GPU's compiler
// and demands the C++ build's bits.
//
// Written in the subset of the two languages that common/brdf.glsl keeps to (float
// literals with an f suffix, no out parameters, no swizzles, no struct
// constructors), after brdf.glsl (BRDF_INLINE, BRDF_PI). Directions are local, the
// normal along +z; densities are per solid angle.
//
// Both sides must round alike, operation for operation, so that the GPU's samples are
// the CPU's: `precise` keeps the GPU's compiler from fusing a multiply and an add that
// C++ rounds twice (C++ defines it away: the CPU tracer is built with
// -ffp-contract=off), and rtDot, rtCross and rtNormalize are glm's dot, cross and
// normalize in glm's order, unfused (rt/math.glsl on the GPU; glm's own in C++,
// core/rt_math.h).

// Frame (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017): s, t,
// n orthonormal around the unit normal n, without a branch on which axis is smallest,
// without normalisation, and without precision loss near either pole.
struct Frame {
  vec3 s, t, n;
};

BRDF_INLINE Frame frameAbout(vec3 n) {
  Frame f;
  f.n = n;
  // copysign(1, n.z) by its bits: -0 counts as negative, as the formula needs.
  float sign = uintBitsToFloat(0x3f800000u | (floatBitsToUint(n.z) & 0x80000000u));
  precise float a = -1.0f / (sign + n.z);
  precise float b = n.x * n.y * a;
  precise vec3 s = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  precise vec3 t = vec3(b, sign + n.y * n.y * a, -n.y);
  f.s = s;
  f.t = t;
  return f;
}

// s along `tangent` made orthogonal to the normal (unit, non-zero), t = n x s.
BRDF_INLINE Frame frameAlong(vec3 n, vec3 tangent) {
  Frame f;
  f.n = n;
  precise vec3 s = tangent - n * rtDot(n, tangent);
  f.s = rtNormalize(s);
  f.t = rtCross(n, f.s);
  return f;
}

BRDF_INLINE vec3 toLocal(Frame f, vec3 w) { return vec3(rtDot(w, f.s), rtDot(w, f.t), rtDot(w, f.n)); }
BRDF_INLINE vec3 toWorld(Frame f, vec3 w) {
  precise vec3 r = w.x * f.s + w.y * f.t + w.z * f.n;
  return r;
}

// (cos a, sin a) for |a| <= pi / 4, by their Taylor polynomials to a^8 and a^9 (the
// first terms left out are below 2.5e-8 and 3.1e-7 there; within 3 ulps of the true
// values, SamplingTest.QuarterSinCosIsWithinThreeUlps). libm's sincosf reduces any
// argument and was 3-4 % of the CPU path tracer's time on the course room; a GPU's
// cos and sin are not exact. The coefficients are 1 / k! rounded to float, written
// out: GLSL leaves to the compiler how exactly it folds a constant division.
BRDF_INLINE vec2 cosSinQuarter(float a) {
  precise float a2 = a * a;
  // 1 - a^2/2! + a^4/4! - a^6/6! + a^8/8!
  precise float c = 1.0f + a2 * (-0.5f + a2 * (0.0416666679f + a2 * (-0.00138888892f + a2 * 2.48015876e-05f)));
  // a - a^3/3! + a^5/5! - a^7/7! + a^9/9!
  precise float s = a * (1.0f + a2 * (-0.166666672f + a2 * (0.00833333377f + a2 * (-0.000198412701f + a2 * 2.75573188e-06f))));
  return vec2(c, s);
}

// Malley's method: a uniform point on the disk lifted to the hemisphere; pdf cos / pi.
// Shirley and Chiu's concentric map keeps strata compact (no squashing at the rim).
BRDF_INLINE vec3 sampleCosineHemisphere(vec2 u) {
  precise vec2 o = 2.0f * u - 1.0f;
  vec2 d = vec2(0.0f);
  if (o.x != 0.0f || o.y != 0.0f) {
    // Each branch's operations chosen by selects, not jumps: which axis is major is a
    // coin toss per sample, and a jump on it was mispredicted half the time. The
    // minor axis's angle a is within pi / 4 of the major axis: (cos a, sin a) about
    // x, or (cos(pi/2 - a), sin(pi/2 - a)) = (sin a, cos a) about y.
    bool xMajor = abs(o.x) > abs(o.y);
    float r = xMajor ? o.x : o.y;
    float other = xMajor ? o.y : o.x;
    precise float a = (BRDF_PI / 4.0f) * (other / r);
    vec2 cs = cosSinQuarter(a);
    precise vec2 disk = r * (xMajor ? cs : vec2(cs.y, cs.x));
    d = disk;
  }
  precise float z = sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}
BRDF_INLINE float cosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0f) / BRDF_PI; }

// Uniform over the cone of directions within acos(cosMax) of +z; pdf 1 / (2 pi (1 - cosMax)).
BRDF_INLINE vec3 sampleUniformCone(vec2 u, float cosMax) {
  precise float cosTheta = (1.0f - u.x) + u.x * cosMax;
  precise float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
  precise float phi = 2.0f * BRDF_PI * u.y;
  precise vec3 w = vec3(cos(phi) * sinTheta, sin(phi) * sinTheta, cosTheta);
  return w;
}
BRDF_INLINE float uniformConePdf(float cosMax) {
  precise float pdf = 1.0f / (2.0f * BRDF_PI * (1.0f - cosMax));
  return pdf;
}

// GGX's Smith Lambda for a direction at cos theta (the same Lambda as brdf.glsl's
// height-correlated visibility): G1 = 1 / (1 + Lambda).
BRDF_INLINE float ggxLambda(float cosTheta, float alpha) {
  precise float c2 = max(cosTheta * cosTheta, 1e-12f);
  precise float tan2 = max(0.0f, 1.0f - c2) / c2;
  precise float lambda = 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
  return lambda;
}
BRDF_INLINE float ggxSmithG1(float cosTheta, float alpha) {
  precise float g1 = 1.0f / (1.0f + ggxLambda(cosTheta, alpha));
  return g1;
}

// KHR_materials_anisotropy's GGX, alpha.x along the local x axis and alpha.y along y
// (Heitz 2014 and 2018 with two roughnesses). Lambda is kept apart from the
// isotropic form above, which every other material's images were made with.
BRDF_INLINE float ggxAnisotropicLambda(vec3 w, vec2 alpha) {
  precise float z2 = max(w.z * w.z, 1e-12f);
  precise float a2Tan2 = (alpha.x * alpha.x * w.x * w.x + alpha.y * alpha.y * w.y * w.y) / z2;
  precise float lambda = 0.5f * (sqrt(1.0f + a2Tan2) - 1.0f);
  return lambda;
}
BRDF_INLINE float ggxAnisotropicG1(vec3 w, vec2 alpha) {
  precise float g1 = 1.0f / (1.0f + ggxAnisotropicLambda(w, alpha));
  return g1;
}

// A microfacet normal drawn from the normals visible from wo (Heitz, "Sampling the
// GGX Distribution of Visible Normals", JCGT 2018): no sample is wasted on facets
// that face away, so grazing views stay as cheap as head-on ones. wo.z > 0. The
// uniform point on the disk comes as its radius r and (cos phi, sin phi), the only
// values that come through GLSL's cos and sin: all else rounds alike in the two
// languages (tests/core/shading_texts_test.cpp holds this part to the bit).
BRDF_INLINE vec3 ggxVisibleNormalAt(vec3 wo, vec2 alpha, float r, vec2 cosSinPhi) {
  vec3 vh = rtNormalize(vec3(alpha.x * wo.x, alpha.y * wo.y, wo.z));
  precise float lensq = vh.x * vh.x + vh.y * vh.y;
  precise vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = rtCross(vh, t1);
  precise float p1 = r * cosSinPhi.x;
  precise float s = 0.5f * (1.0f + vh.z);
  precise float p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * r * cosSinPhi.y;
  precise vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return rtNormalize(vec3(alpha.x * nh.x, alpha.y * nh.y, max(1e-6f, nh.z)));
}
BRDF_INLINE vec3 sampleGgxAnisotropicVisibleNormal(vec3 wo, vec2 alpha, vec2 u) {
  precise float phi = 2.0f * BRDF_PI * u.y;
  return ggxVisibleNormalAt(wo, alpha, sqrt(u.x), vec2(cos(phi), sin(phi)));
}
// The isotropic lobe is the anisotropic sampler with equal alphas: the same
// operations, the same bits.
BRDF_INLINE vec3 sampleGgxVisibleNormal(vec3 wo, float alpha, vec2 u) {
  return sampleGgxAnisotropicVisibleNormal(wo, vec2(alpha), u);
}

// D(h) for a local h, in brdf.glsl's stable form (sin^2 from x and y, not 1 - cos^2).
BRDF_INLINE float ggxD(vec3 h, float alpha) {
  precise float a = h.z * alpha;
  precise float k = alpha / max(h.x * h.x + h.y * h.y + a * a, 1e-30f);
  precise float d = k * k / BRDF_PI;
  return d;
}

// The density of wi = reflect(-wo, h) with h from sampleGgxVisibleNormal:
// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
BRDF_INLINE float ggxReflectionPdf(vec3 wo, vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  precise vec3 sum = wo + wi;
  vec3 h = rtNormalize(sum);
  precise float pdf = ggxSmithG1(wo.z, alpha) * ggxD(h, alpha) / (4.0f * wo.z);
  return pdf;
}

// The same for the anisotropic GGX (alpha.x along x, alpha.y along y).
BRDF_INLINE float ggxAnisotropicD(vec3 h, vec2 alpha) {
  precise float a2 = alpha.x * alpha.y;
  precise vec3 f = vec3(alpha.y * h.x, alpha.x * h.y, a2 * h.z);
  precise float w2 = a2 / max(rtDot(f, f), 1e-30f);
  precise float d = a2 * w2 * w2 / BRDF_PI;
  return d;
}
BRDF_INLINE float ggxAnisotropicReflectionPdf(vec3 wo, vec3 wi, vec2 alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  precise vec3 sum = wo + wi;
  vec3 h = rtNormalize(sum);
  precise float pdf = ggxAnisotropicG1(wo, alpha) * ggxAnisotropicD(h, alpha) / (4.0f * wo.z);
  return pdf;
}

// w mirrored about the unit h.
BRDF_INLINE vec3 reflectAbout(vec3 w, vec3 h) {
  precise vec3 r = 2.0f * rtDot(w, h) * h - w;
  return r;
}

// Veach's power heuristic (beta = 2) for a sample of strategy f, with one sample
// taken from each of the two strategies.
BRDF_INLINE float powerHeuristic(float fPdf, float gPdf) {
  precise float f2 = fPdf * fPdf;
  precise float g2 = gPdf * gPdf;
  precise float sum = f2 + g2;
  return sum > 0.0f ? f2 / sum : 0.0f;
}
