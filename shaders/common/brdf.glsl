// The engine's two material models, written once. GLSL includes this file
// (common/shading.glsl); C++ compiles the very same text with GLM (engine/core/brdf.h),
// and the ray tracers evaluate it. tests/gl/brdf_test.cpp runs both, the GLSL in a
// compute shader, over a grid of angles and parameters and demands agreement.
//
// So this file is written in what the two languages share: float literals with an f
// suffix (C++ would make 1.0 a double, and glm's operators take no mixed types), no
// out or inout parameters, no struct constructors, no swizzles, no overloads that
// differ only by return type. Vectors are unit length and point away from the surface.
//
// CLASSIC is the course's model: what a light of unit radiance reflects is
// albedo * diffuse * N.L plus a Blinn-Phong highlight specular * (N.H)^shininess.
// METALLIC-ROUGHNESS is glTF's: a Lambert lobe weighted by (1 - F) (1 - metallic) and
// a GGX lobe with the height-correlated Smith visibility and Schlick's Fresnel.
//
// Light intensities are the radiance a white Lambert surface facing the light
// reflects (the rasterizer's convention), so a renderer multiplies a BRDF by
// PI * N.L * radiance; brdfLightFactor says so once.

// C++ defines BRDF_INLINE as inline (one definition in every translation unit);
// GLSL has no such keyword and no need of it.
#ifndef BRDF_INLINE
#define BRDF_INLINE
#endif

const float BRDF_PI = 3.14159265358979f;

// The course's highlight and diffuse for one light of unit radiance, N.L included.
BRDF_INLINE vec3 classicReflected(vec3 n, vec3 toEye, vec3 l, vec3 albedo, float diffuse, float specular, float shininess) {
  float nDotL = max(dot(n, l), 0.0f);
  vec3 h = normalize(l + toEye);
  // Most course materials have no highlight: pow() is the costliest call here.
  float highlight = nDotL > 0.0f && specular > 0.0f ? specular * pow(max(dot(n, h), 0.0f), shininess) : 0.0f;
  return albedo * (diffuse * nDotL) + vec3(highlight);
}

// Trowbridge-Reitz (GGX) normal distribution, alpha = roughness^2, in the form
// alpha^2 / (pi (sin^2 + alpha^2 cos^2)^2) with sin^2 = |n x h|^2 (Filament's): the
// textbook 1 + cos^2 (alpha^2 - 1) cancels catastrophically near the peak of a smooth
// lobe, where cos^2 rounds by 6e-8 and alpha^2 is 1e-6 (a 6 % error in D; the GPU's
// and the CPU's roundings then disagree by that much).
BRDF_INLINE float ggxDistribution(vec3 n, vec3 h, float alpha) {
  vec3 nxh = cross(n, h);
  float a = dot(n, h) * alpha;
  float k = alpha / max(dot(nxh, nxh) + a * a, 1e-30f);
  return k * k / BRDF_PI;
}

// The height-correlated Smith masking-shadowing over 4 N.L N.V (Heitz 2014, eq. 99;
// glTF's spec, appendix B): the specular lobe is F * D * V.
BRDF_INLINE float smithVisibility(float nDotL, float nDotV, float alpha) {
  float a2 = alpha * alpha;
  float gl = nDotV * sqrt(nDotL * nDotL * (1.0f - a2) + a2);
  float gv = nDotL * sqrt(nDotV * nDotV * (1.0f - a2) + a2);
  return 0.5f / max(gl + gv, 1e-6f);
}

// Schlick's Fresnel, (1 - cos)^5 by multiplication: pow() is not exact on every GPU.
BRDF_INLINE vec3 schlickFresnel(vec3 f0, float vDotH) {
  float m = clamp(1.0f - vDotH, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// The same with a grazing reflectance f90 below 1 (KHR_materials_specular). With
// f90 = 1 it is schlickFresnel to the last bit.
BRDF_INLINE vec3 schlickFresnel90(vec3 f0, float f90, float vDotH) {
  float m = clamp(1.0f - vDotH, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(f90) - f0) * (m2 * m2 * m);
}

// The roughness a GGX lobe is drawn with: squared, and kept off zero, where the
// distribution becomes a delta that no light sample can hit.
BRDF_INLINE float ggxAlpha(float roughness) { return max(roughness * roughness, 1e-3f); }

// A dielectric reflects 4 % at normal incidence; a metal its albedo.
BRDF_INLINE vec3 metallicF0(vec3 albedo, float metallic) { return mix(vec3(0.04f), albedo, metallic); }

// The metallic-roughness BRDF f(l, v), without the cosine; zero below the surface.
BRDF_INLINE vec3 metallicRoughnessBrdf(vec3 n, vec3 toEye, vec3 l, vec3 albedo, float metallic, float roughness) {
  float nDotL = dot(n, l);
  if (nDotL <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(l + toEye);
  float nDotV = max(dot(n, toEye), 1e-4f);
  float vDotH = max(dot(toEye, h), 0.0f);
  float alpha = ggxAlpha(roughness);
  vec3 fresnel = schlickFresnel(metallicF0(albedo, metallic), vDotH);
  vec3 specular = fresnel * (ggxDistribution(n, h, alpha) * smithVisibility(nDotL, nDotV, alpha));
  vec3 diffuse = (vec3(1.0f) - fresnel) * albedo * ((1.0f - metallic) / BRDF_PI);
  return diffuse + specular;
}

// The same BRDF with glTF's dielectric layers (KHR_materials_ior, _specular,
// _clearcoat), as the Khronos Sample Viewer draws them:
// - the dielectric reflects dielectricF0 at normal incidence and dielectricF90 at
//   grazing angles (0.04 and 1 without the extensions; asset/material_layers.h
//   computes them from ior and the specular weight and colour);
// - a clear coat of weight `clearcoat`, a GGX lobe of ior 1.5 (f0 0.04) along its own
//   normal nc, lies over that base, which loses what the coat reflects toward the
//   eye: f = base (1 - clearcoat Fc(nc.v)) + clearcoat Fc(v.h) D V.
// - KHR_materials_transmission passes the share `transmission` of the dielectric's
//   diffuse lobe through the surface instead (transmittedShare below says what comes
//   back through it); what is left of the lobe reflects.
// With dielectricF0 = 0.04, dielectricF90 = 1, no coat and no transmission it equals
// metallicRoughnessBrdf (tests/gl/brdf_test.cpp).
BRDF_INLINE vec3 layeredBrdf(vec3 n, vec3 toEye, vec3 l, vec3 albedo, float metallic, float roughness,
                             vec3 dielectricF0, float dielectricF90, vec3 nc, float clearcoat,
                             float clearcoatRoughness, float transmission) {
  vec3 base = vec3(0.0f);
  float nDotL = dot(n, l);
  if (nDotL > 0.0f) {
    vec3 h = normalize(l + toEye);
    float nDotV = max(dot(n, toEye), 1e-4f);
    float vDotH = max(dot(toEye, h), 0.0f);
    float alpha = ggxAlpha(roughness);
    vec3 f0 = mix(dielectricF0, albedo, metallic);
    float f90 = dielectricF90 + (1.0f - dielectricF90) * metallic;
    vec3 fresnel = schlickFresnel90(f0, f90, vDotH);
    vec3 specular = fresnel * (ggxDistribution(n, h, alpha) * smithVisibility(nDotL, nDotV, alpha));
    base = (vec3(1.0f) - fresnel) * albedo * ((1.0f - metallic) * (1.0f - transmission) / BRDF_PI) + specular;
  }
  if (clearcoat <= 0.0f) return base;
  float ncDotV = max(dot(nc, toEye), 1e-4f);
  vec3 coat = vec3(0.0f);
  float ncDotL = dot(nc, l);
  if (ncDotL > 0.0f) {
    vec3 hc = normalize(l + toEye);
    float alphaC = ggxAlpha(clearcoatRoughness);
    coat = schlickFresnel(vec3(0.04f), max(dot(toEye, hc), 0.0f)) *
           (ggxDistribution(nc, hc, alphaC) * smithVisibility(ncDotL, ncDotV, alphaC));
  }
  float attenuation = 1.0f - clearcoat * schlickFresnel(vec3(0.04f), ncDotV).x;
  return base * attenuation + coat * clearcoat;
}

// The cheapest ambient's share of a sky colour (render.ambient "hemisphere"): the
// diffuse colour, a guess at the specular's, and the coat's the same way over the
// base it dims. Not physical: the path tracer and the IBL ambient replace it.
BRDF_INLINE vec3 hemisphereAmbient(vec3 albedo, float metallic, float roughness, vec3 dielectricF0, float nDotV,
                                   float clearcoat, float clearcoatRoughness, float transmission) {
  vec3 f0 = mix(dielectricF0, albedo, metallic);
  vec3 base = albedo * ((1.0f - metallic) * (1.0f - transmission)) + f0 * (1.0f - roughness) * 0.5f;
  if (clearcoat <= 0.0f) return base;
  float coat = clearcoat * schlickFresnel(vec3(0.04f), nDotV).x;
  return base * (1.0f - coat) + vec3(clearcoat * 0.04f * (1.0f - clearcoatRoughness) * 0.5f);
}

// KHR_materials_transmission: the share of the light arriving from behind, along the
// refracted ray (straight on, through a thin wall), that leaves toward the eye: what
// the surface does not reflect (`reflected`, its specular albedo toward the eye: the
// split-sum table's f0 A + f90 B in the rasterizer, Fresnel in the Whitted tracer),
// tinted by the base colour, for the dielectric's transmitted share (the Khronos
// Sample Viewer's model).
BRDF_INLINE vec3 transmittedShare(vec3 albedo, float metallic, float transmission, vec3 reflected) {
  return (vec3(1.0f) - reflected) * albedo * ((1.0f - metallic) * transmission);
}

// KHR_materials_volume: what is left of light after `distance` through the medium
// (Beer-Lambert): attenuationColor after each attenuationDistance; 0 means infinite.
BRDF_INLINE vec3 volumeAttenuation(vec3 attenuationColor, float attenuationDistance, float distance) {
  if (attenuationDistance <= 0.0f) return vec3(1.0f);
  return pow(attenuationColor, vec3(distance / attenuationDistance));
}

// The roughness a transmitted image is blurred with: none at ior 1 (the light does
// not bend), the surface's from ior 1.5 on (the Sample Viewer's applyIorToRoughness).
BRDF_INLINE float transmissionRoughness(float roughness, float ior) {
  return roughness * clamp(ior * 2.0f - 2.0f, 0.0f, 1.0f);
}

// What a light of radiance 1 arriving along l reflects through a BRDF value f:
// f * N.L * PI (see the convention above).
BRDF_INLINE vec3 brdfLightFactor(vec3 f, float nDotL) { return f * (max(nDotL, 0.0f) * BRDF_PI); }
