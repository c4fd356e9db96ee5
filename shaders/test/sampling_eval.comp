#version 450 core
// tests/core/shading_texts_test.cpp: the path tracers' sampling routines
// (common/sampling.glsl) on the GPU's compiler, for random inputs, so that the C++
// build of the same text (core/sampling.h) can be compared case by case.
#include "rt/math.glsl"
#include "common/brdf.glsl"
#include "common/sampling.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 n;        // xyz: a unit normal; w: an angle for cosSinQuarter
  vec4 tangent;  // xyz: unit, not along n; w: a cone's cos
  vec4 w;        // xyz: a unit direction, local or world; w: a roughness alpha
  vec4 wi;       // xyz: a second unit direction (local); w: a second alpha
  vec4 u;        // xy: two uniform numbers; zw: two pdfs for the power heuristic
  vec4 disk;     // x: sqrt(u.x); yz: cos and sin of 2 pi u.y, from C++
};

struct Result {
  vec4 aboutS, aboutT;  // frameAbout(n): s, t
  vec4 alongS, alongT;  // frameAlong(n, tangent): s, t
  vec4 local, world;    // toLocal and toWorld of w in frameAbout(n); local.w: cosSinQuarter's cos, world.w its sin
  vec4 cosine;          // sampleCosineHemisphere(u); w: cosineHemispherePdf(wi.z)
  vec4 cone;            // sampleUniformCone(u, cosMax); w: uniformConePdf(cosMax)
  vec4 visible;         // sampleGgxVisibleNormal(w, alpha, u); w: ggxSmithG1(w.z, alpha)
  vec4 anisotropic;     // sampleGgxAnisotropicVisibleNormal(w, alphas, u); w: ggxAnisotropicG1(w, alphas)
  vec4 reflected;       // reflectAbout(w, wi); w: powerHeuristic
  vec4 pdfs;            // ggxD(wi, alpha), ggxReflectionPdf, ggxAnisotropicD(wi, alphas), ggxAnisotropicReflectionPdf
  vec4 lambdas;         // ggxLambda, ggxAnisotropicLambda
  vec4 visibleAt;       // ggxVisibleNormalAt(w, alphas, disk): the visible normal without GLSL's cos and sin
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  vec3 n = c.n.xyz, w = c.w.xyz, wi = c.wi.xyz;
  vec2 u = c.u.xy, alphas = vec2(c.w.w, c.wi.w);
  float alpha = c.w.w, cosMax = c.tangent.w;
  Result r;
  Frame about = frameAbout(n), along = frameAlong(n, c.tangent.xyz);
  vec2 cs = cosSinQuarter(c.n.w);
  r.aboutS = vec4(about.s, 0.0);
  r.aboutT = vec4(about.t, 0.0);
  r.alongS = vec4(along.s, 0.0);
  r.alongT = vec4(along.t, 0.0);
  r.local = vec4(toLocal(about, w), cs.x);
  r.world = vec4(toWorld(about, w), cs.y);
  r.cosine = vec4(sampleCosineHemisphere(u), cosineHemispherePdf(wi.z));
  r.cone = vec4(sampleUniformCone(u, cosMax), uniformConePdf(cosMax));
  r.visible = vec4(sampleGgxVisibleNormal(w, alpha, u), ggxSmithG1(w.z, alpha));
  r.anisotropic = vec4(sampleGgxAnisotropicVisibleNormal(w, alphas, u), ggxAnisotropicG1(w, alphas));
  r.reflected = vec4(reflectAbout(w, wi), powerHeuristic(c.u.z, c.u.w));
  r.pdfs = vec4(ggxD(wi, alpha), ggxReflectionPdf(w, wi, alpha), ggxAnisotropicD(wi, alphas),
                ggxAnisotropicReflectionPdf(w, wi, alphas));
  r.lambdas = vec4(ggxLambda(w.z, alpha), ggxAnisotropicLambda(w, alphas), 0.0, 0.0);
  r.visibleAt = vec4(ggxVisibleNormalAt(w, alphas, c.disk.x, c.disk.yz), 0.0);
  results[i] = r;
}
