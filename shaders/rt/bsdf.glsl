// The path tracer's scattering at one hit (raytrace/bsdf.cpp) for what the GPU path
// tracer draws: the classic model made physical (Lambert, the course's highlight and
// the mirror) and metallic-roughness (Lambert + GGX, with KHR_materials_ior and
// _specular's f0 and f90). Clear coat, sheen, transmission, anisotropy and
// iridescence are refused before a kernel runs, so their shares are 0 here and
// their branches of bsdf.cpp are left out. The BRDFs are common/brdf.glsl's, the
// text the CPU evaluates; the lobe choice and its pdf are bsdf.cpp's, transcribed.
// After rt/sampling.glsl, rt/materials.glsl and common/brdf.glsl.

struct Bsdf {
  bool metallicRoughness;
  vec3 albedo;
  float diffuse, specular, shininess, reflection, metallic, roughness;
  vec3 dielectricF0;
  float dielectricF90;
  Frame frame;
  vec3 wo, woLocal;
  float alpha;      // GGX
  float pMirror;    // classic: the mirror's share of the samples
  float pSpecular;  // metallic-roughness: the GGX lobe's share
};

struct BsdfSample {
  vec3 wi;
  vec3 weight;  // f |cos| / pdf
  float pdf;    // 0 for the mirror's delta
  bool delta;
};

float meanOf(vec3 c) {
  precise float m = (c.x + c.y + c.z) / 3.0;
  return m;
}

Bsdf bsdfOf(RtMaterial m, bool metallicRoughness, vec3 n, vec3 wo) {
  Bsdf b;
  b.metallicRoughness = metallicRoughness;
  b.albedo = m.colorAmbient.xyz;
  b.diffuse = m.diffuseSpecularShininessReflection.x;
  b.specular = m.diffuseSpecularShininessReflection.y;
  b.shininess = m.diffuseSpecularShininessReflection.z;
  b.reflection = m.diffuseSpecularShininessReflection.w;
  b.metallic = m.metallicRoughnessUnlit.x;
  b.roughness = m.metallicRoughnessUnlit.y;
  b.dielectricF0 = m.dielectric.xyz;
  b.dielectricF90 = m.dielectric.w;
  b.frame = frameAbout(n);
  b.wo = wo;
  b.woLocal = toLocal(b.frame, wo);
  b.alpha = 1.0;
  b.pMirror = 0.0;
  b.pSpecular = 0.0;
  if (!metallicRoughness) {
    // Bsdf::classic: samples follow each part's weight.
    precise float rest = b.diffuse * max(b.albedo.x, max(b.albedo.y, b.albedo.z)) + b.specular;
    float mirror = max(b.reflection, 0.0);
    precise float share = mirror / (mirror + rest);
    b.pMirror = mirror > 0.0 ? (rest > 0.0 ? share : 1.0) : 0.0;
    return b;
  }
  // Bsdf::metallicRoughness without layers: sheen scale 1, no coat, no transmission.
  b.alpha = ggxAlpha(b.roughness);
  float cosO = clamp(b.woLocal.z, 0.0, 1.0);
  vec3 f0 = mix(b.dielectricF0, b.albedo, b.metallic);
  precise float f90 = b.dielectricF90 + (1.0 - b.dielectricF90) * b.metallic;
  float fresnel = meanOf(schlickFresnel90(f0, f90, cosO));
  precise float diffuse = meanOf(b.albedo) * (1.0 - b.metallic) * (1.0 - fresnel);
  precise float share = fresnel / (fresnel + diffuse);
  b.pSpecular = diffuse > 0.0 ? clamp(share, 0.1, 0.9) : 1.0;
  return b;
}

// Bsdf::f: the BRDF for wi (world, unit), the mirror excluded.
vec3 bsdfF(Bsdf b, vec3 wi) {
  float cosI = rtDot(b.frame.n, wi);
  if (cosI <= 0.0 || b.woLocal.z <= 0.0) return vec3(0.0);
  if (!b.metallicRoughness) {
    if (b.specular <= 0.0) return b.albedo * (b.diffuse / BRDF_PI);
    vec3 reflected = classicReflected(b.frame.n, b.wo, wi, b.albedo, b.diffuse, b.specular, b.shininess);
    return reflected / (BRDF_PI * cosI);
  }
  return layeredBrdf(b.frame.n, b.wo, wi, b.albedo, b.metallic, b.roughness, b.dielectricF0, b.dielectricF90,
                     b.frame.n, 0.0, 0.0, 0.0, vec3(0.0), 0.0, 1.0, b.frame.s, b.frame.t, 0.0, vec3(0.0), 0.0);
}

// Bsdf::pdf: the density sample() draws wi with through its non-delta lobes.
float bsdfPdf(Bsdf b, vec3 wi) {
  vec3 wiLocal = toLocal(b.frame, wi);
  if (wiLocal.z <= 0.0 || b.woLocal.z <= 0.0) return 0.0;
  if (!b.metallicRoughness) {
    precise float pdf = (1.0 - b.pMirror) * cosineHemispherePdf(wiLocal.z);
    return pdf;
  }
  precise float base = b.pSpecular * ggxReflectionPdf(b.woLocal, wiLocal, b.alpha) +
                       (1.0 - b.pSpecular) * cosineHemispherePdf(wiLocal.z);
  return base;
}

// Bsdf::sample with its mirror, lambertSample and reflectionSample; false when it
// draws nothing.
bool bsdfSample(Bsdf b, vec2 u, float uLobe, out BsdfSample s) {
  s.wi = vec3(0.0, 0.0, 1.0);
  s.weight = vec3(0.0);
  s.pdf = 0.0;
  s.delta = false;
  if (b.woLocal.z <= 0.0) return false;
  if (!b.metallicRoughness && uLobe < b.pMirror) {
    s.wi = toWorld(b.frame, vec3(-b.woLocal.x, -b.woLocal.y, b.woLocal.z));
    s.weight = vec3(b.reflection / b.pMirror);
    s.delta = true;
    return true;
  }
  if (!b.metallicRoughness && b.specular <= 0.0) {
    // lambertSample: f cos / pdf needs no evaluation.
    vec3 wiLocal = sampleCosineHemisphere(u);
    if (wiLocal.z <= 0.0) return false;
    s.wi = toWorld(b.frame, wiLocal);
    precise float pdf = (1.0 - b.pMirror) * cosineHemispherePdf(wiLocal.z);
    s.pdf = pdf;
    s.weight = b.albedo * (b.diffuse / (1.0 - b.pMirror));
    return true;
  }
  // reflectionSample (the transmission's share is 0, so uLobe is unchanged).
  vec3 wiLocal = b.metallicRoughness && uLobe < b.pSpecular
                     ? reflectAbout(b.woLocal, sampleGgxVisibleNormal(b.woLocal, b.alpha, u))
                     : sampleCosineHemisphere(u);
  if (wiLocal.z <= 0.0) return false;
  s.wi = rtNormalize(toWorld(b.frame, wiLocal));
  s.pdf = bsdfPdf(b, s.wi);
  if (!(s.pdf > 0.0)) return false;
  s.weight = bsdfF(b, s.wi) * (rtDot(b.frame.n, s.wi) / s.pdf);
  return true;
}
