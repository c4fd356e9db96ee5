// The two material models. CLASSIC is the course's: colour * (ambient + diffuse *
// N.L * visibility) (+ a Blinn-Phong highlight); mirrors add reflection * the
// environment. PBR is glTF's metallic-roughness with GGX, Smith and Schlick.
struct Surface {
  vec3 albedo;
  vec3 n;
  vec3 toEye;
  vec3 position;
  float metallic;
  float roughness;
  float ambient;
  float diffuse;
  float specular;
  float shininess;
  float reflection;
};

// The BRDFs themselves live in common/brdf.glsl, which the C++ tracers compile too.
#include "common/brdf.glsl"

const float PI = BRDF_PI;

#ifdef MATERIAL_LAYERS
// glTF's ior, specular and clear coat (asset/material_layers.h), for the PBR model
// only: layeredBrdf in place of metallicRoughnessBrdf, and the coat's reflection in
// the ambient. Materials without them never build this variant. The fragment
// shader sets these before shading (common/material.glsl's materialLayers).
vec3 g_dielectricF0;
float g_dielectricF90;
float g_clearcoat;
float g_clearcoatRoughness;
vec3 g_clearcoatNormal;
float g_transmission;  // KHR_materials_transmission's share, 0 without it
float g_thickness;     // KHR_materials_volume's, in the mesh's units
#endif

#ifdef SHEEN
// KHR_materials_sheen: its colour and roughness at the fragment, the white sheen's
// directional albedo E there (core/sheen_table.h's table) and the scaling it leaves
// what lies under the sheen, both once per fragment (surfaceSheen below).
layout(binding = UNIT_SHEEN_ALBEDO) uniform sampler2D u_sheenAlbedo;
vec3 g_sheenColor;
float g_sheenRoughness;
float g_sheenAlbedo;
float g_sheenScale;

void surfaceSheen(Surface s) {
  g_sheenAlbedo = texture(u_sheenAlbedo, sheenTableCoord(dot(s.n, s.toEye), g_sheenRoughness)).r;
  g_sheenScale = sheenScaling(g_sheenColor, g_sheenAlbedo);
}
#else
// No sheen: constants, so that the layered code folds it away.
const vec3 g_sheenColor = vec3(0.0);
const float g_sheenRoughness = 0.0;
const float g_sheenAlbedo = 0.0;
const float g_sheenScale = 1.0;
#endif

#ifdef ANISOTROPY
// KHR_materials_anisotropy at the fragment (material.glsl's materialAnisotropy): the
// stretch's direction, the one across it, and its strength.
vec3 g_anisotropyT;
vec3 g_anisotropyB;
float g_anisotropy;
#else
const vec3 g_anisotropyT = vec3(1.0, 0.0, 0.0);
const vec3 g_anisotropyB = vec3(0.0, 1.0, 0.0);
const float g_anisotropy = 0.0;
#endif

#ifdef IRIDESCENCE
// KHR_materials_iridescence at the fragment: the film's share and thickness
// (material.glsl's materialLayers) and its Fresnel at N.V (surfaceIridescence, once
// per fragment).
uniform float u_iridescenceIor;
float g_iridescence;
float g_iridescenceThickness;
vec3 g_iridescenceF;

vec3 surfaceIridescence(Surface s) {
  vec3 f0 = mix(g_dielectricF0, s.albedo, s.metallic);
  return iridescenceFresnel(1.0, u_iridescenceIor, max(dot(s.n, s.toEye), 1e-4), g_iridescenceThickness, f0);
}
#else
const float g_iridescence = 0.0;
const vec3 g_iridescenceF = vec3(0.0);
#endif

#ifdef CLASSIC
vec3 shadeAmbient(Surface s) { return s.albedo * s.ambient; }

vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
#ifdef CLASSIC_MATTE
  // A material without a highlight (ShaderVariant::matte): the same value, without
  // the highlight's code, which llvmpipe would run for every fragment anyway.
  return radiance * visibility * classicDiffuse(s.n, l, s.albedo, s.diffuse);
#else
  return radiance * visibility *
         classicReflected(s.n, s.toEye, l, s.albedo, s.diffuse, s.specular, s.shininess);
#endif
}
#elif defined(AMBIENT_SH) || defined(AMBIENT_IBL)
// The environment's light, as the path tracer integrates it, by the split sum (Karis
// 2013): the diffuse lobe sees the SH irradiance E(n), weighted by its mean 1 - F;
// the specular the environment's radiance around the mirror direction times the
// lobe's directional albedo f0 A + B (the BRDF table, render/ibl.h). Under
// AMBIENT_IBL that radiance is the GGX-prefiltered cube at the surface's roughness;
// under AMBIENT_SH it is E(r) / pi, the environment as blurred as a Lambert lobe
// sees it: right for rough surfaces, too dull a highlight on smooth ones.
#include "common/ibl_sampling.glsl"
layout(binding = UNIT_SPLIT_SUM) uniform sampler2D u_splitSum;
#ifdef AMBIENT_IBL
layout(binding = UNIT_PREFILTERED) uniform samplerCube u_prefiltered;
#endif

// Written out with constant indices, so that each shBasis folds to its polynomial
// when compiled, whether or not a compiler unrolls a loop and folds its branches.
vec3 shIrradiance(vec3 n) {
  vec3 e = u_shIrradiance[0].rgb * shBasis(0, n) + u_shIrradiance[1].rgb * shBasis(1, n) +
           u_shIrradiance[2].rgb * shBasis(2, n) + u_shIrradiance[3].rgb * shBasis(3, n) +
           u_shIrradiance[4].rgb * shBasis(4, n) + u_shIrradiance[5].rgb * shBasis(5, n) +
           u_shIrradiance[6].rgb * shBasis(6, n) + u_shIrradiance[7].rgb * shBasis(7, n) +
           u_shIrradiance[8].rgb * shBasis(8, n);
  return max(e, vec3(0.0));  // order 2 rings below zero behind a bright sun
}

// The environment's radiance around direction r as a lobe of `roughness` sees it.
vec3 ambientRadiance(vec3 r, float roughness) {
#ifdef AMBIENT_IBL
  return textureLod(u_prefiltered, r, roughness * u_iblParams.x).rgb;
#else
  return shIrradiance(r) / PI;
#endif
}

vec3 shadeAmbient(Surface s) {
  float nDotV = max(dot(s.n, s.toEye), 1e-4);
  vec3 table = texture(u_splitSum, vec2(nDotV, s.roughness)).rgb;
#ifdef MATERIAL_LAYERS
  vec3 f0 = mix(g_dielectricF0, s.albedo, s.metallic);
  float f90 = g_dielectricF90 + (1.0 - g_dielectricF90) * s.metallic;
#else
  vec3 f0 = metallicF0(s.albedo, s.metallic);
#endif
#ifdef MATERIAL_LAYERS
  vec3 diffuse = (vec3(1.0) - f0) * (table.z * (1.0 - s.metallic) * (1.0 - g_transmission)) * s.albedo *
                 shIrradiance(s.n) / PI;
#else
  vec3 diffuse = (vec3(1.0) - f0) * (table.z * (1.0 - s.metallic)) * s.albedo * shIrradiance(s.n) / PI;
#endif
#ifdef ANISOTROPY
  vec3 reflectAbout = anisotropicReflectionNormal(s.n, s.toEye, g_anisotropyB, g_anisotropy, s.roughness);
#else
  vec3 reflectAbout = s.n;
#endif
  vec3 radiance = ambientRadiance(reflect(-s.toEye, reflectAbout), s.roughness);
#ifdef MATERIAL_LAYERS
  vec3 color = diffuse + radiance * (f0 * table.x + vec3(f90 * table.y));
#ifdef IRIDESCENCE
  // The film's Fresnel at N.V in place of the split sum's f0 scale and bias (the
  // Sample Viewer's shortcut).
  color = mix(color, diffuse + radiance * g_iridescenceF * (table.x + table.y), g_iridescence);
#endif
#ifdef SHEEN
  // The sheen's broad lobe sees the environment as a Lambert lobe does (a shortcut:
  // the Sample Viewer prefilters a Charlie-lobe cube of its own).
  color = color * g_sheenScale + g_sheenColor * (g_sheenAlbedo / PI) * shIrradiance(s.n);
#endif
  if (g_clearcoat <= 0.0) return color;
  // The coat (f0 0.04) by the same split sum along its own normal, over the base it dims.
  vec3 nc = g_clearcoatNormal;
  float ncDotV = max(dot(nc, s.toEye), 1e-4);
  vec3 coatTable = texture(u_splitSum, vec2(ncDotV, g_clearcoatRoughness)).rgb;
  float coat = g_clearcoat * schlickFresnel(vec3(0.04), ncDotV).x;
  vec3 coatRadiance = ambientRadiance(reflect(-s.toEye, nc), g_clearcoatRoughness);
  return color * (1.0 - coat) + g_clearcoat * coatRadiance * (0.04 * coatTable.x + coatTable.y);
#else
  return diffuse + radiance * (f0 * table.x + vec3(table.y));
#endif
}
#else
// The cheapest ambient (render.ambient "hemisphere"): two colours of the sky mixed by
// the normal, and a guess at the specular's share.
vec3 shadeAmbient(Surface s) {
  vec3 sky = mix(u_ambientGround.rgb, u_ambientSky.rgb, 0.5 + 0.5 * s.n.y);
#ifdef MATERIAL_LAYERS
  float ncDotV = max(dot(g_clearcoatNormal, s.toEye), 1e-4);
  return sky * hemisphereAmbient(s.albedo, s.metallic, s.roughness, g_dielectricF0, ncDotV, g_clearcoat,
                                 g_clearcoatRoughness, g_transmission, g_sheenColor, g_sheenAlbedo, g_iridescenceF,
                                 g_iridescence);
#else
  vec3 diffuseColor = s.albedo * (1.0 - s.metallic);
  vec3 f0 = metallicF0(s.albedo, s.metallic);
  return sky * (diffuseColor + f0 * (1.0 - s.roughness) * 0.5);
#endif
}
#endif

#ifndef CLASSIC
vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
  float nDotL = dot(s.n, l);
  if (nDotL <= 0.0 || visibility <= 0.0) return vec3(0.0);
#ifdef MATERIAL_LAYERS
  vec3 f = layeredBrdf(s.n, s.toEye, l, s.albedo, s.metallic, s.roughness, g_dielectricF0, g_dielectricF90,
                       g_clearcoatNormal, g_clearcoat, g_clearcoatRoughness, g_transmission, g_sheenColor,
                       g_sheenRoughness, g_sheenScale, g_anisotropyT, g_anisotropyB,
                       g_anisotropy, g_iridescenceF, g_iridescence);
#else
  vec3 f = metallicRoughnessBrdf(s.n, s.toEye, l, s.albedo, s.metallic, s.roughness);
#endif
  return radiance * visibility * brdfLightFactor(f, nDotL);
}
#endif

#ifdef REFLECTION_PROBES
// A mirror reflects the cube map of the scene seen from its centre: right in
// direction, off by parallax for things close to the mirror, one bounce only. The
// ray tracer traces the reflected ray itself; the difference is measured.
layout(binding = UNIT_REFLECTION_PROBE) uniform samplerCube u_reflectionProbe;
uniform int u_hasProbe;

vec3 reflectedEnvironment(Surface s) {
  if (u_hasProbe == 0 || s.reflection <= 0.0) return vec3(0.0);
  return s.reflection * texture(u_reflectionProbe, reflect(-s.toEye, s.n)).rgb;
}
#else
// Without probes a mirror shows only its own shading.
vec3 reflectedEnvironment(Surface s) { return vec3(0.0 * s.reflection); }
#endif
