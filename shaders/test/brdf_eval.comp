#version 450 core
// tests/core/brdf_test.cpp: evaluates common/brdf.glsl on the GPU's compiler for a grid
// of cases, so that the C++ build of the same text (core/brdf.h) can be compared.
#include "common/brdf.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 n;          // xyz
  vec4 toEye;      // xyz
  vec4 l;          // xyz
  vec4 albedo;     // xyz
  vec4 params;     // metallic, roughness, diffuse, specular
  vec4 shininess;  // x
  vec4 dielectric; // xyz dielectricF0, w dielectricF90
  vec4 coat;       // clearcoat, clearcoat roughness, transmission, sheen albedo E
  vec4 nc;         // xyz: the coat's normal
  vec4 sheen;      // xyz sheen colour, w sheen roughness
  vec4 anisotropy; // xyz the stretch's direction, w its strength
  vec4 iridescence; // xyz the film's Fresnel, w its share
};

struct Result {
  vec4 metallicRoughness;  // xyz
  vec4 classic;            // xyz
  vec4 terms;              // ggxDistribution, smithVisibility, ggxAlpha
  vec4 fresnel;            // xyz
  vec4 layered;            // xyz
  vec4 hemisphere;         // xyz
  vec4 transmitted;        // xyz transmittedShare x volumeAttenuation, w transmissionRoughness
  vec4 sheenTerms;         // charlieDistribution, sheenVisibility, sheenLambda, sheenBrdf
  vec4 anisotropic;        // xyz anisotropicReflectionNormal, w anisotropyDirection's x
  vec4 film;               // xyz iridescenceFresnel
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  vec3 n = c.n.xyz, v = c.toEye.xyz, l = c.l.xyz;
  float metallic = c.params.x, roughness = c.params.y;
  vec3 h = normalize(l + v);
  float alpha = ggxAlpha(roughness);
  Result r;
  r.metallicRoughness = vec4(metallicRoughnessBrdf(n, v, l, c.albedo.xyz, metallic, roughness), 0.0);
  r.classic = vec4(classicReflected(n, v, l, c.albedo.xyz, c.params.z, c.params.w, c.shininess.x), 0.0);
  r.terms = vec4(ggxDistribution(n, h, alpha),
                 smithVisibility(max(dot(n, l), 0.0), max(dot(n, v), 1e-4), alpha), alpha, 0.0);
  r.fresnel = vec4(schlickFresnel(metallicF0(c.albedo.xyz, metallic), max(dot(v, h), 0.0)), 0.0);
  r.layered = vec4(layeredBrdf(n, v, l, c.albedo.xyz, metallic, roughness, c.dielectric.xyz, c.dielectric.w, c.nc.xyz,
                               c.coat.x, c.coat.y, c.coat.z, c.sheen.xyz, c.sheen.w, sheenScaling(c.sheen.xyz, c.coat.w),
                               c.anisotropy.xyz, cross(n, c.anisotropy.xyz), c.anisotropy.w, c.iridescence.xyz,
                               c.iridescence.w),
                   0.0);
  r.hemisphere = vec4(hemisphereAmbient(c.albedo.xyz, metallic, roughness, c.dielectric.xyz,
                                        max(dot(c.nc.xyz, v), 1e-4), c.coat.x, c.coat.y, c.coat.z, c.sheen.xyz, c.coat.w,
                                        c.iridescence.xyz, c.iridescence.w),
                      0.0);
  float nDotL = max(dot(n, l), 1e-4), nDotV = max(dot(n, v), 1e-4);
  float sheenA = sheenAlpha(roughness);
  r.sheenTerms = vec4(charlieDistribution(n, h, sheenA), sheenVisibility(nDotL, nDotV, sheenA),
                      sheenLambda(nDotV, sheenA), sheenBrdf(n, v, l, roughness));
  float strength = c.anisotropy.w > 0.0 ? c.anisotropy.w : 0.7;
  r.anisotropic = vec4(anisotropicReflectionNormal(n, v, cross(n, c.anisotropy.xyz), strength, roughness),
                       anisotropyDirection(vec2(0.6, 0.8), 3.0 * roughness - 1.0).x);
  r.film = vec4(iridescenceFresnel(1.0, 1.2 + 2.0 * c.params.w * roughness, nDotV, 1000.0 * roughness,
                                   metallicF0(c.albedo.xyz, metallic)),
                0.0);
  vec3 reflected = schlickFresnel90(c.dielectric.xyz, c.dielectric.w, max(dot(n, v), 1e-4));
  r.transmitted = vec4(transmittedShare(c.albedo.xyz, metallic, c.coat.z, reflected) *
                           volumeAttenuation(c.albedo.xyz, 0.5, 0.1 + roughness),
                       transmissionRoughness(roughness, 1.0 + c.params.w * c.coat.z));
  results[i] = r;
}
