// The engine's two material models, written once. GLSL includes this file
// (common/shading.glsl); C++ compiles the very same text with GLM (engine/core/brdf.h),
// and the ray tracers evaluate it. tests/core/brdf_test.cpp runs both, the GLSL in a
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

// The course's diffuse term for one light of unit radiance, N.L included: all that
// classicReflected gives for a material without a highlight (specular 0), to the bit.
BRDF_INLINE vec3 classicDiffuse(vec3 n, vec3 l, vec3 albedo, float diffuse) {
  return albedo * (diffuse * max(dot(n, l), 0.0f));
}

// The course's highlight and diffuse for one light of unit radiance, N.L included.
BRDF_INLINE vec3 classicReflected(vec3 n, vec3 toEye, vec3 l, vec3 albedo, float diffuse, float specular, float shininess) {
  float nDotL = max(dot(n, l), 0.0f);
  vec3 h = normalize(l + toEye);
  // Most course materials have no highlight: pow() is the costliest call here.
  float highlight = nDotL > 0.0f && specular > 0.0f ? specular * pow(max(dot(n, h), 0.0f), shininess) : 0.0f;
  return classicDiffuse(n, l, albedo, diffuse) + vec3(highlight);
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

// KHR_materials_anisotropy: the base's GGX lobe stretched along a direction t in the
// surface (b = n x t), as glTF's spec and the Khronos Sample Viewer define it:
// alpha along t is mix(alpha, 1, anisotropy^2), along b alpha itself. The
// distribution in Filament's form (no cancellation near the peak, as ggxDistribution).
BRDF_INLINE float anisotropicAlpha(float alpha, float anisotropy) { return mix(alpha, 1.0f, anisotropy * anisotropy); }

BRDF_INLINE float ggxAnisotropicDistribution(vec3 n, vec3 h, vec3 t, vec3 b, float alphaT, float alphaB) {
  float a2 = alphaT * alphaB;
  vec3 f = vec3(alphaB * dot(t, h), alphaT * dot(b, h), a2 * dot(n, h));
  float w2 = a2 / max(dot(f, f), 1e-30f);
  return a2 * w2 * w2 / BRDF_PI;
}

// The anisotropic height-correlated Smith visibility (Heitz 2014), over 4 N.L N.V.
BRDF_INLINE float smithAnisotropicVisibility(vec3 n, vec3 toEye, vec3 l, vec3 t, vec3 b, float alphaT, float alphaB) {
  float nDotL = dot(n, l);
  float nDotV = max(dot(n, toEye), 1e-4f);
  float gv = nDotL * length(vec3(alphaT * dot(t, toEye), alphaB * dot(b, toEye), nDotV));
  float gl = nDotV * length(vec3(alphaT * dot(t, l), alphaB * dot(b, l), nDotL));
  return 0.5f / max(gv + gl, 1e-6f);
}

// The direction of the stretch in the tangent frame: the texture's (or +x), turned by
// anisotropyRotation counter-clockwise (toward the bitangent).
BRDF_INLINE vec2 anisotropyDirection(vec2 direction, float rotation) {
  float c = cos(rotation);
  float s = sin(rotation);
  return vec2(c * direction.x - s * direction.y, s * direction.x + c * direction.y);
}

// The base's specular D V: isotropic GGX, or stretched along t (anisotropy > 0).
BRDF_INLINE float baseSpecularDV(vec3 n, vec3 toEye, vec3 l, vec3 h, float alpha, vec3 t, vec3 b, float anisotropy) {
  if (anisotropy <= 0.0f)
    return ggxDistribution(n, h, alpha) * smithVisibility(dot(n, l), max(dot(n, toEye), 1e-4f), alpha);
  float alphaT = anisotropicAlpha(alpha, anisotropy);
  return ggxAnisotropicDistribution(n, h, t, b, alphaT, alpha) *
         smithAnisotropicVisibility(n, toEye, l, t, b, alphaT, alpha);
}

// The normal an anisotropic surface reflects its environment about (the Sample
// Viewer's bent normal): turned toward the direction across the stretch, the more so
// the stronger and smoother. The split-sum ambients read the environment along it.
BRDF_INLINE vec3 anisotropicReflectionNormal(vec3 n, vec3 toEye, vec3 b, float anisotropy, float roughness) {
  vec3 bent = normalize(cross(cross(b, toEye), b));
  float k = 1.0f - anisotropy * (1.0f - roughness);
  float a = k * k * k * k;
  return normalize(mix(bent, n, a));
}

// KHR_materials_iridescence: a thin film of index filmIor and `thickness` nanometres
// over the base, whose two interfaces' reflections interfere (Belcour and Barla 2017,
// "A Practical Extension to Microfacet Theory for the Modeling of Varying
// Iridescence", as glTF's spec and the Khronos Sample Viewer evaluate it): the
// Fresnel reflectance at cos theta1 of the film over a base of reflectance baseF0,
// seen from a medium of index outsideIor (air: 1).
BRDF_INLINE float iorToF0(float transmittedIor, float incidentIor) {
  float r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
  return r * r;
}
BRDF_INLINE vec3 iorToF0Rgb(vec3 transmittedIor, float incidentIor) {
  vec3 r = (transmittedIor - vec3(incidentIor)) / (transmittedIor + vec3(incidentIor));
  return r * r;
}
BRDF_INLINE vec3 f0ToIor(vec3 f0) {
  vec3 root = sqrt(f0);
  return (vec3(1.0f) + root) / (vec3(1.0f) - root);
}
BRDF_INLINE float schlickScalar(float f0, float cosTheta) {
  float m = clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}

// The eye's response to an optical path difference `opd` (nm) at phase `shift`, as
// linear Rec. 709 RGB: Belcour and Barla's Gaussian fit of the CIE XYZ matching
// functions in Fourier space, turned to RGB.
BRDF_INLINE vec3 iridescenceSensitivity(float opd, vec3 shift) {
  float phase = 2.0f * BRDF_PI * opd * 1.0e-9f;
  vec3 val = vec3(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  vec3 pos = vec3(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  vec3 var = vec3(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  vec3 xyz = val * sqrt(2.0f * BRDF_PI * var) * cos(pos * phase + shift) * exp(-(phase * phase) * var);
  float x = xyz.x + 9.7470e-14f * sqrt(2.0f * BRDF_PI * 4.5282e+09f) * cos(2.2399e+06f * phase + shift.x) *
                        exp(-4.5282e+09f * (phase * phase));
  vec3 c = vec3(x, xyz.y, xyz.z) / 1.0685e-7f;
  // XYZ to linear Rec. 709, row by row.
  return vec3(3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
              -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
              0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z);
}

BRDF_INLINE vec3 iridescenceFresnel(float outsideIor, float filmIor, float cosTheta1, float thickness, vec3 baseF0) {
  // A film thinner than 30 nm fades into the outside medium (no film at 0).
  float t = clamp(thickness / 30.0f, 0.0f, 1.0f);
  float ior = mix(outsideIor, filmIor, t * t * (3.0f - 2.0f * t));
  float ratio = outsideIor / ior;
  float cosTheta2Sq = 1.0f - ratio * ratio * (1.0f - cosTheta1 * cosTheta1);
  if (cosTheta2Sq < 0.0f) return vec3(1.0f);  // total internal reflection in the film
  float cosTheta2 = sqrt(cosTheta2Sq);
  // The first interface, outside to film.
  float r12 = schlickScalar(iorToF0(ior, outsideIor), cosTheta1);
  float t121 = 1.0f - r12;
  float phi12 = ior < outsideIor ? BRDF_PI : 0.0f;
  float phi21 = BRDF_PI - phi12;
  // The second, film to base (each channel's index from its f0).
  vec3 baseIor = f0ToIor(clamp(baseF0, vec3(0.0f), vec3(0.9999f)));
  vec3 r1 = iorToF0Rgb(baseIor, ior);
  float m = clamp(1.0f - cosTheta2, 0.0f, 1.0f);
  float m2 = m * m;
  vec3 r23 = r1 + (vec3(1.0f) - r1) * (m2 * m2 * m);
  vec3 phi23 = vec3(baseIor.x < ior ? BRDF_PI : 0.0f, baseIor.y < ior ? BRDF_PI : 0.0f, baseIor.z < ior ? BRDF_PI : 0.0f);
  float opd = 2.0f * ior * thickness * cosTheta2;
  vec3 phi = vec3(phi21) + phi23;
  vec3 r123 = clamp(r12 * r23, vec3(1e-5f), vec3(0.9999f));
  vec3 root123 = sqrt(r123);
  vec3 rs = (t121 * t121) * r23 / (vec3(1.0f) - r123);
  // The mean term, then two pairs of interference terms.
  vec3 reflectance = vec3(r12) + rs;
  vec3 cm = rs - vec3(t121);
  cm = cm * root123;
  reflectance = reflectance + cm * (2.0f * iridescenceSensitivity(opd, phi));
  cm = cm * root123;
  reflectance = reflectance + cm * (2.0f * iridescenceSensitivity(2.0f * opd, 2.0f * phi));
  return max(reflectance, vec3(0.0f));
}

// KHR_materials_sheen: a layer of fibres over the base, the "Charlie" distribution
// (Estevez and Kulla 2017, "Production Friendly Microfacet Sheen BRDF") with their
// fitted visibility, as glTF's spec and the Khronos Sample Viewer define them. The
// distribution's alpha is the sheen roughness squared, kept off zero as ggxAlpha is.
BRDF_INLINE float sheenAlpha(float sheenRoughness) { return max(sheenRoughness * sheenRoughness, 1e-3f); }

// (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), with sin^2 = |n x h|^2 (no
// cancellation near n = h, where the power of a small difference would magnify it).
BRDF_INLINE float charlieDistribution(vec3 n, vec3 h, float alpha) {
  vec3 nxh = cross(n, h);
  float invAlpha = 1.0f / alpha;
  return (2.0f + invAlpha) * pow(dot(nxh, nxh), invAlpha * 0.5f) / (2.0f * BRDF_PI);
}

// Estevez and Kulla's fit of the Charlie distribution's log Lambda at cos theta = x,
// its coefficients interpolated by (1 - alpha)^2.
BRDF_INLINE float sheenLambdaFit(float x, float alpha) {
  float t = (1.0f - alpha) * (1.0f - alpha);
  float a = mix(21.5473f, 25.3245f, t);
  float b = mix(3.82987f, 3.32435f, t);
  float c = mix(0.19823f, 0.16801f, t);
  float d = mix(-1.97760f, -1.27393f, t);
  float e = mix(-4.32054f, -4.85967f, t);
  return a / (1.0f + b * pow(max(x, 0.0f), c)) + d * x + e;  // x may round past 1 - 1
}

// Lambda itself, with the fit's soft terminator above 60 degrees of cos theta.
BRDF_INLINE float sheenLambda(float cosTheta, float alpha) {
  if (cosTheta < 0.5f) return exp(sheenLambdaFit(cosTheta, alpha));
  return exp(2.0f * sheenLambdaFit(0.5f, alpha) - sheenLambdaFit(1.0f - cosTheta, alpha));
}

// The sheen's masking-shadowing over 4 N.L N.V, kept in [0, 1] as the Sample Viewer's.
BRDF_INLINE float sheenVisibility(float nDotL, float nDotV, float alpha) {
  float v = 1.0f / ((1.0f + sheenLambda(nDotV, alpha) + sheenLambda(nDotL, alpha)) * (4.0f * nDotV * nDotL));
  return clamp(v, 0.0f, 1.0f);
}

// The sheen BRDF for a white sheen colour, without the cosine (N.L > 0).
BRDF_INLINE float sheenBrdf(vec3 n, vec3 toEye, vec3 l, float sheenRoughness) {
  float alpha = sheenAlpha(sheenRoughness);
  vec3 h = normalize(l + toEye);
  return charlieDistribution(n, h, alpha) * sheenVisibility(dot(n, l), max(dot(n, toEye), 1e-4f), alpha);
}

BRDF_INLINE float maxComponent(vec3 c) { return max(c.x, max(c.y, c.z)); }

// The white sheen's directional albedo E is a table (core/sheen_table.h) of this
// size, read at sqrt(N.V) across (E changes fastest at grazing views) and the sheen
// roughness up, the first and last texel centres on 0 and 1, so that a linear
// filter needs no clamping at the edges.
const float SHEEN_TABLE_SIZE = 32.0f;
BRDF_INLINE vec2 sheenTableCoord(float nDotV, float sheenRoughness) {
  vec2 t = vec2(sqrt(clamp(nDotV, 0.0f, 1.0f)), clamp(sheenRoughness, 0.0f, 1.0f));
  return (t * (SHEEN_TABLE_SIZE - 1.0f) + vec2(0.5f)) / SHEEN_TABLE_SIZE;
}

// What the sheen leaves to the layers under it toward the eye (albedo scaling):
// 1 - max(sheenColor) E, E the white sheen's directional albedo at N.V and the sheen
// roughness (core/sheen_table.h computes its table from sheenBrdf above; the
// rasterizer samples it as a texture, the tracers look it up). Kept at 0 or above:
// at grazing views E exceeds 1 (core/sheen_table.h says why).
BRDF_INLINE float sheenScaling(vec3 sheenColor, float sheenAlbedo) {
  return max(1.0f - maxComponent(sheenColor) * sheenAlbedo, 0.0f);
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
// - KHR_materials_anisotropy stretches the base's GGX lobe along anisotropyT
//   (anisotropyB across it; baseSpecularDV above).
// - KHR_materials_iridescence replaces the base's Fresnel by the thin film's,
//   iridescenceF (iridescenceFresnel above, at N.V, once per shading point), by the
//   share `iridescence`; the diffuse lobe loses the film's strongest channel.
// - KHR_materials_sheen lies between the two: over the base (and what it transmits)
//   a sheen lobe of colour sheenColor, which dims the base by sheenScaling (above):
//   f = sheenColor sheenBrdf + base sheenScaling, all under the coat.
// With dielectricF0 = 0.04, dielectricF90 = 1, no coat, no transmission and no sheen
// it equals metallicRoughnessBrdf (tests/core/brdf_test.cpp).
BRDF_INLINE vec3 layeredBrdf(vec3 n, vec3 toEye, vec3 l, vec3 albedo, float metallic, float roughness,
                             vec3 dielectricF0, float dielectricF90, vec3 nc, float clearcoat,
                             float clearcoatRoughness, float transmission, vec3 sheenColor, float sheenRoughness,
                             float sheenScale, vec3 anisotropyT, vec3 anisotropyB, float anisotropy,
                             vec3 iridescenceF, float iridescence) {
  vec3 base = vec3(0.0f);
  float nDotL = dot(n, l);
  if (nDotL > 0.0f) {
    vec3 h = normalize(l + toEye);
    float vDotH = max(dot(toEye, h), 0.0f);
    float alpha = ggxAlpha(roughness);
    vec3 f0 = mix(dielectricF0, albedo, metallic);
    float f90 = dielectricF90 + (1.0f - dielectricF90) * metallic;
    vec3 fresnel = schlickFresnel90(f0, f90, vDotH);
    vec3 diffuseFresnel = fresnel;
    if (iridescence > 0.0f) {
      diffuseFresnel = mix(fresnel, vec3(maxComponent(iridescenceF)), iridescence);
      fresnel = mix(fresnel, iridescenceF, iridescence);
    }
    vec3 specular = fresnel * baseSpecularDV(n, toEye, l, h, alpha, anisotropyT, anisotropyB, anisotropy);
    base = (vec3(1.0f) - diffuseFresnel) * albedo * ((1.0f - metallic) * (1.0f - transmission) / BRDF_PI) + specular;
    if (maxComponent(sheenColor) > 0.0f)
      base = base * sheenScale + sheenColor * sheenBrdf(n, toEye, l, sheenRoughness);
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
// base it dims; the sheen reflects its directional albedo sheenAlbedo (the table's E)
// over the base it dims. Not physical: the path tracer and the IBL ambient replace it.
BRDF_INLINE vec3 hemisphereAmbient(vec3 albedo, float metallic, float roughness, vec3 dielectricF0, float nDotV,
                                   float clearcoat, float clearcoatRoughness, float transmission, vec3 sheenColor,
                                   float sheenAlbedo, vec3 iridescenceF, float iridescence) {
  vec3 f0 = mix(dielectricF0, albedo, metallic);
  if (iridescence > 0.0f) f0 = mix(f0, iridescenceF, iridescence);
  vec3 base = albedo * ((1.0f - metallic) * (1.0f - transmission)) + f0 * (1.0f - roughness) * 0.5f;
  if (maxComponent(sheenColor) > 0.0f) base = base * sheenScaling(sheenColor, sheenAlbedo) + sheenColor * sheenAlbedo;
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
