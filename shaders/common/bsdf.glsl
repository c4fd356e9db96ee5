// The path tracers' scattering at one hit, written once: the GPU path tracer
// includes this file (through rt/bsdf.glsl, which unpacks its material buffer), and
// C++ compiles the very same text (engine/core/bsdf.h) for the CPU path tracer
// (raytrace/bsdf.h wraps it in the Bsdf class its callers use). tests/gl/
// gpu_bsdf_test.cpp runs both compiles over random materials, directions and random
// numbers and compares them case by case; tests/raytrace/sampling_test.cpp and
// path_tracer_test.cpp judge the CPU's side statistically.
//
// CLASSIC, made physical: the course's diffuse and highlight divided by pi N.L (what
// its shadeLight multiplies a light by) are the BRDF, drawn with cosine-weighted
// directions; `reflection` is a perfect mirror of that weight, untinted, as in the
// Whitted tracer. Its `ambient` has no place here: indirect light replaces it.
// METALLIC-ROUGHNESS: brdf.glsl's Lambert + GGX (layeredBrdf, with glTF's ior,
// specular and clear coat), drawn by a mix of cosine-weighted directions and GGX
// visible normals of the base and of the coat, the mix following the lobes' Fresnel
// weights; an anisotropic base (KHR_materials_anisotropy) draws its visible normals
// from the stretched GGX in a frame whose x follows the stretch. A sheen
// (KHR_materials_sheen) over the base has a lobe of uniform directions in the mix:
// its lobe leans to the horizon, where cosine-weighted directions are rare (measured:
// 0.3 to 0.8 times their estimate's standard deviation, the least at low roughness and
// grazing views). The coat's normal is the shading normal: the tracers read no normal
// maps. KHR_materials_transmission adds a lobe through the surface, the dielectric's
// transmitted share (brdf.glsl's transmittedShare: what its Fresnel does not reflect,
// tinted by the base colour): GGX visible normals refract the ray by the ior into a
// volume (KHR_materials_volume; total internal reflection keeps it inside), or turn
// the facet's mirror direction through a thin wall. No light sample can be weighed
// against it (shadow rays stop at the surface), so it is drawn alone and counts what
// it finds in full, as a mirror does.
//
// In the subset of the two languages that common/sampling.glsl keeps to, after it,
// common/brdf.glsl and common/view_layers.glsl. BRDF_IN(T) is how a function takes a
// Bsdf: by value in GLSL, by const reference in C++ (a Bsdf is some 60 floats, and
// f and pdf are called for every light sample). rtDot, rtNormalize, mixAsGlm and
// refractAsGlm are glm's dot, normalize, mix and refract; `precise` keeps the GPU from
// fusing what C++ rounds twice.

#ifndef BRDF_IN
#define BRDF_IN(T) T
#endif

// What a hit's material gives the scattering.
struct BsdfMaterial {
  vec3 albedo;
  float diffuse, specular, shininess, reflection;  // classic
  float metallic, roughness;
  vec3 dielectricF0;
  float dielectricF90;
  float clearcoat, clearcoatRoughness;
  vec3 sheenColor;
  float sheenRoughness, iridescence;
  float transmission, ior, thickness;  // thickness 0: a thin wall
};

struct Bsdf {
  BsdfMaterial m;
  bool metallicRoughness;
  bool entering;  // the viewer is outside the surface (its front face): which way a volume's ior bends
  Frame frame;    // about the shading normal; x along the stretch of an anisotropic base
  vec3 wo, woLocal;
  float alpha;       // GGX, metallic-roughness only
  vec2 alphas;       // KHR_materials_anisotropy: the base lobe's alphas along frame.s and frame.t
  float anisotropy;  // ViewLayers' anisotropy: 0 where there is no stretch to orient
  float alphaCoat;
  float pMirror;    // classic: the mirror's share of the samples
  float pSpecular;  // metallic-roughness: the GGX lobe's share of the base's samples
  float pSheen;     // the sheen's share of the samples under the coat
  float pCoat;      // the clear coat's share of all reflected samples
  float pTransmit;  // the transmission lobe's share of all samples
  float alphaTransmit;
  // ViewLayers: the scaling the sheen leaves the base; the film's Fresnel at N.V.
  float sheenScale;
  vec3 iridescenceF;
};

struct BsdfSample {
  bool drawn;        // false: nothing (the direction fell under the surface, or a zero pdf)
  vec3 wi;           // world, unit
  vec3 weight;       // f |cos| / pdf: what the path's throughput is multiplied by
  float pdf;         // of the lobe mixture; 0 for a delta
  bool delta;        // a mirror or transmitted direction: no light sample can find it
  bool transmitted;  // through the surface (KHR_materials_transmission)
};

BRDF_INLINE float bsdfMean(vec3 c) {
  precise float m = (c.x + c.y + c.z) / 3.0f;
  return m;
}

// A lobe choice u in [0, 1) past a share p taken before it, rescaled to [0, 1) again
// (unchanged where p is 0).
BRDF_INLINE float pastShare(float u, float p) {
  precise float r = (u - p) / (1.0f - p);
  return r;
}

// For the unit shading normal n on the viewer's side and wo (unit, toward the
// viewer): the frame and, for the classic model, the mirror's share. A
// metallic-roughness Bsdf is finished by bsdfViewed, with the view's terms at
// N.V = bsdfCosView(b) (the caller looks up its sheen table for them).
BRDF_INLINE Bsdf bsdfAbout(BRDF_IN(BsdfMaterial) m, bool metallicRoughness, vec3 n, vec3 wo, bool entering) {
  Bsdf b;
  b.m = m;
  b.metallicRoughness = metallicRoughness;
  b.entering = entering;
  b.frame = frameAbout(n);
  b.wo = wo;
  b.woLocal = toLocal(b.frame, wo);
  b.alpha = 1.0f;
  b.alphas = vec2(1.0f);
  b.anisotropy = 0.0f;
  b.alphaCoat = 1.0f;
  b.pMirror = 0.0f;
  b.pSpecular = 0.0f;
  b.pSheen = 0.0f;
  b.pCoat = 0.0f;
  b.pTransmit = 0.0f;
  b.alphaTransmit = 1.0f;
  b.sheenScale = 1.0f;
  b.iridescenceF = vec3(0.0f);
  if (!metallicRoughness) {
    // Samples follow each part's weight, so a 0.8 mirror gets most of them.
    precise float rest = m.diffuse * max(m.albedo.x, max(m.albedo.y, m.albedo.z)) + m.specular;
    float mirror = max(m.reflection, 0.0f);
    b.pMirror = mirror > 0.0f ? (rest > 0.0f ? mirror / (mirror + rest) : 1.0f) : 0.0f;
  }
  return b;
}

BRDF_INLINE float bsdfCosView(BRDF_IN(Bsdf) b) { return clamp(b.woLocal.z, 0.0f, 1.0f); }

// The metallic-roughness lobes' shares, given the view's terms at bsdfCosView (n the
// normal bsdfAbout took). Each share is kept inside [0.1, 0.9] while its lobes exist:
// a lobe never sampled would leave its light to the light samples alone, and MIS could
// not weigh it.
BRDF_INLINE Bsdf bsdfViewed(Bsdf b, vec3 n, ViewLayers view) {
  float cosO = bsdfCosView(b);
  b.alpha = ggxAlpha(b.m.roughness);
  if (view.anisotropy > 0.0f) {
    // KHR_materials_anisotropy: the local frame's x along the stretch.
    b.frame = frameAlong(n, view.anisotropyT);
    b.woLocal = toLocal(b.frame, b.wo);
    b.anisotropy = view.anisotropy;
    // brdf.glsl's anisotropicAlpha with glm::mix's rounding (GLSL's mix may round otherwise).
    precise float squared = b.anisotropy * b.anisotropy;
    b.alphas = vec2(mixAsGlm(b.alpha, 1.0f, squared), b.alpha);
  }
  b.sheenScale = view.sheenScale;
  b.iridescenceF = view.iridescenceF;
  vec3 f0 = mixAsGlm(b.m.dielectricF0, b.m.albedo, b.m.metallic);
  precise float f90 = b.m.dielectricF90 + (1.0f - b.m.dielectricF90) * b.m.metallic;
  float fresnel = bsdfMean(mixAsGlm(schlickFresnel90(f0, f90, cosO), b.iridescenceF, b.m.iridescence));
  // A sheen dims what lies under it by its albedo scaling.
  precise float sheen = maxComponent(b.m.sheenColor) * view.sheenAlbedo;
  precise float specular = fresnel * b.sheenScale;
  precise float diffuse =
      bsdfMean(b.m.albedo) * (1.0f - b.m.metallic) * (1.0f - b.m.transmission) * (1.0f - fresnel) * b.sheenScale;
  b.pSpecular = diffuse > 0.0f ? clamp(specular / (specular + diffuse), 0.1f, 0.9f) : 1.0f;
  if (sheen > 0.0f) {
    precise float under = specular + diffuse;
    b.pSheen = under > 0.0f ? clamp(sheen / (sheen + under), 0.1f, 0.9f) : 1.0f;
  }
  // The coat reflects clearcoat Fc toward the eye and passes the rest to what lies
  // under it: the base's reflection and the transmission alike.
  precise float coat = b.m.clearcoat > 0.0f ? b.m.clearcoat * schlickFresnel(vec3(0.04f), cosO).x : 0.0f;
  if (b.m.clearcoat > 0.0f) {
    precise float base = (1.0f - coat) * (specular + diffuse + sheen);
    b.alphaCoat = ggxAlpha(b.m.clearcoatRoughness);
    b.pCoat = base > 0.0f ? clamp(coat / (coat + base), 0.1f, 0.9f) : 1.0f;
  }
  if (b.m.transmission > 0.0f && b.m.metallic < 1.0f) {
    precise float through = bsdfMean(b.m.albedo) * (1.0f - b.m.metallic) * b.m.transmission * (1.0f - fresnel) *
                            (1.0f - coat) * b.sheenScale;
    precise float reflected = coat + (1.0f - coat) * (specular + diffuse + sheen);
    b.pTransmit = reflected > 0.0f ? clamp(through / (through + reflected), 0.1f, 0.9f) : 1.0f;
    // A thin wall blurs what is behind it as much as its ior bends (none at 1); a
    // volume's facets refract at the surface's own roughness.
    b.alphaTransmit =
        ggxAlpha(b.m.thickness > 0.0f ? b.m.roughness : transmissionRoughness(b.m.roughness, b.m.ior));
  }
  return b;
}

// The BRDF for the light's direction wi (world, unit), the mirror excluded.
BRDF_INLINE vec3 bsdfF(BRDF_IN(Bsdf) b, vec3 wi) {
  float cosI = rtDot(b.frame.n, wi);
  if (cosI <= 0.0f || b.woLocal.z <= 0.0f) return vec3(0.0f);
  if (!b.metallicRoughness) {
    // Without a highlight classicReflected / (pi N.L) is the Lambert term exactly.
    if (b.m.specular <= 0.0f) return b.m.albedo * (b.m.diffuse / BRDF_PI);
    vec3 reflected =
        classicReflected(b.frame.n, b.wo, wi, b.m.albedo, b.m.diffuse, b.m.specular, b.m.shininess);
    return reflected / (BRDF_PI * cosI);
  }
  return layeredBrdf(b.frame.n, b.wo, wi, b.m.albedo, b.m.metallic, b.m.roughness, b.m.dielectricF0,
                     b.m.dielectricF90, b.frame.n, b.m.clearcoat, b.m.clearcoatRoughness, b.m.transmission,
                     b.m.sheenColor, b.m.sheenRoughness, b.sheenScale, b.frame.s, b.frame.t, b.anisotropy,
                     b.iridescenceF, b.m.iridescence);
}

// The density bsdfSampleOf draws wi with through its non-delta lobes (solid angle).
BRDF_INLINE float bsdfPdf(BRDF_IN(Bsdf) b, vec3 wi) {
  vec3 wiLocal = toLocal(b.frame, wi);
  if (wiLocal.z <= 0.0f || b.woLocal.z <= 0.0f) return 0.0f;
  if (!b.metallicRoughness) {
    precise float pdf = (1.0f - b.pMirror) * cosineHemispherePdf(wiLocal.z);
    return pdf;
  }
  float specular = b.anisotropy > 0.0f ? ggxAnisotropicReflectionPdf(b.woLocal, wiLocal, b.alphas)
                                       : ggxReflectionPdf(b.woLocal, wiLocal, b.alpha);
  precise float base = b.pSpecular * specular + (1.0f - b.pSpecular) * cosineHemispherePdf(wiLocal.z);
  if (b.pSheen > 0.0f) {
    precise float withSheen = b.pSheen * uniformConePdf(0.0f) + (1.0f - b.pSheen) * base;
    base = withSheen;
  }
  precise float reflected =
      b.pCoat <= 0.0f ? base : b.pCoat * ggxReflectionPdf(b.woLocal, wiLocal, b.alphaCoat) + (1.0f - b.pCoat) * base;
  precise float pdf = (1.0f - b.pTransmit) * reflected;
  return pdf;
}

BRDF_INLINE BsdfSample bsdfNothing() {
  BsdfSample s;
  s.drawn = false;
  s.wi = vec3(0.0f, 0.0f, 1.0f);
  s.weight = vec3(0.0f);
  s.pdf = 0.0f;
  s.delta = false;
  s.transmitted = false;
  return s;
}

// Through the surface by the visible normal h: the ray refracted by it into a volume
// (or mirrored by it inside, past the critical angle), or mirrored by it and turned
// through a thin wall. The weight is what the layered model passes, (1 - F(wo.h))
// times the base colour and transmission, times G1 of the new direction
// (visible-normal sampling leaves no other factor), over the lobe's share.
BRDF_INLINE BsdfSample bsdfTransmitted(BRDF_IN(Bsdf) b, vec3 h) {
  BsdfSample s = bsdfNothing();
  float cosO = rtDot(b.woLocal, h);
  if (!(cosO > 0.0f)) return s;
  vec3 fresnel = schlickFresnel90(b.m.dielectricF0, b.m.dielectricF90, cosO);
  precise vec3 share =
      (vec3(1.0f) - fresnel) * b.m.albedo * ((1.0f - b.m.metallic) * b.m.transmission * b.sheenScale);
  vec3 wiLocal;
  if (b.m.thickness > 0.0f) {
    float eta = b.entering ? 1.0f / max(b.m.ior, 1.0f) : max(b.m.ior, 1.0f);
    wiLocal = refractAsGlm(-b.woLocal, h, eta);
    if (wiLocal == vec3(0.0f)) {
      // Total internal reflection: what the reflection lobe's Fresnel did not take
      // stays inside as well.
      wiLocal = reflectAbout(b.woLocal, h);
      if (wiLocal.z <= 0.0f) return s;
    } else if (wiLocal.z >= 0.0f) {
      return s;
    }
  } else {
    wiLocal = reflectAbout(b.woLocal, h);
    if (wiLocal.z <= 0.0f) return s;
    wiLocal.z = -wiLocal.z;
  }
  s.drawn = true;
  s.wi = rtNormalize(toWorld(b.frame, wiLocal));
  precise vec3 weight = share * (ggxSmithG1(abs(wiLocal.z), b.alphaTransmit) / b.pTransmit);
  s.weight = weight;
  s.delta = true;
  s.transmitted = wiLocal.z < 0.0f;
  return s;
}

// A direction for two uniform numbers u, the lobe chosen by uLobe (uniform too).
BRDF_INLINE BsdfSample bsdfSampleOf(BRDF_IN(Bsdf) b, vec2 u, float uLobe) {
  BsdfSample s = bsdfNothing();
  if (b.woLocal.z <= 0.0f) return s;
  if (!b.metallicRoughness && uLobe < b.pMirror) {
    s.drawn = true;
    s.wi = toWorld(b.frame, vec3(-b.woLocal.x, -b.woLocal.y, b.woLocal.z));
    s.weight = vec3(b.m.reflection / b.pMirror);
    s.delta = true;
    return s;
  }
  if (!b.metallicRoughness && b.m.specular <= 0.0f) {
    // The course's diffuse alone: f cos / pdf is (albedo diffuse / pi) cos over
    // (1 - pMirror) cos / pi, so the weight needs no evaluation (a third of a bounce's
    // shading time in the course room).
    vec3 wiLocal = sampleCosineHemisphere(u);
    if (wiLocal.z <= 0.0f) return s;
    s.drawn = true;
    s.wi = toWorld(b.frame, wiLocal);
    precise float pdf = (1.0f - b.pMirror) * cosineHemispherePdf(wiLocal.z);
    s.pdf = pdf;
    s.weight = b.m.albedo * (b.m.diffuse / (1.0f - b.pMirror));
    return s;
  }
  // Through the surface with the transmission's share; else above it with uLobe
  // rescaled past that share: the coat, the sheen, the GGX lobe or the diffuse one,
  // each past the shares before it. One call site for the three GGX lobes' visible
  // normals (llvmpipe inlines every call; the isotropic sampler is the anisotropic one
  // with equal alphas, the same bits).
  float rest = pastShare(uLobe, b.pTransmit);
  float pastCoat = pastShare(rest, b.pCoat);
  int lobe = uLobe < b.pTransmit                           ? 4
             : !b.metallicRoughness                        ? 3
             : rest < b.pCoat                              ? 0
             : pastCoat < b.pSheen                         ? 1
             : pastShare(pastCoat, b.pSheen) < b.pSpecular ? 2
                                                           : 3;
  vec3 h = vec3(0.0f, 0.0f, 1.0f);
  if (lobe == 0 || lobe == 2 || lobe == 4) {
    vec2 alpha = lobe == 0   ? vec2(b.alphaCoat)
                 : lobe == 2 ? (b.anisotropy > 0.0f ? b.alphas : vec2(b.alpha))
                             : vec2(b.alphaTransmit);
    h = sampleGgxAnisotropicVisibleNormal(b.woLocal, alpha, u);
  }
  if (lobe == 4) return bsdfTransmitted(b, h);
  vec3 wiLocal;
  if (lobe == 1) {
    wiLocal = sampleUniformCone(u, 0.0f);
  } else if (lobe == 3) {
    wiLocal = sampleCosineHemisphere(u);
  } else {
    wiLocal = reflectAbout(b.woLocal, h);
  }
  if (wiLocal.z <= 0.0f) return s;  // the facet reflected it below the surface
  s.wi = rtNormalize(toWorld(b.frame, wiLocal));
  s.pdf = bsdfPdf(b, s.wi);
  if (!(s.pdf > 0.0f)) return s;
  s.drawn = true;
  s.weight = bsdfF(b, s.wi) * (rtDot(b.frame.n, s.wi) / s.pdf);
  return s;
}
