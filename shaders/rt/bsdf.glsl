// The path tracer's scattering at one hit (raytrace/bsdf.cpp) for what the GPU path
// tracer draws: the classic model made physical (Lambert, the course's highlight and
// the mirror) and metallic-roughness (Lambert + GGX, with KHR_materials_ior and
// _specular's f0 and f90, the clear coat, the sheen, the thin film, transmission
// through thin walls and into volumes, and anisotropy). The BRDFs are common/brdf.glsl's, the
// text the CPU evaluates; the lobe choice and its pdf are bsdf.cpp's, and the view's
// terms rt/view_layers.glsl's. After common/sampling.glsl, rt/materials.glsl,
// rt/environment_light.glsl, common/brdf.glsl and rt/view_layers.glsl.

struct Bsdf {
  bool metallicRoughness;
  vec3 albedo;
  float diffuse, specular, shininess, reflection, metallic, roughness;
  vec3 dielectricF0;
  float dielectricF90;
  float clearcoat, clearcoatRoughness;
  vec3 sheenColor;
  float sheenRoughness, iridescence;
  float transmission, ior, thickness;
  bool entering;  // the ray comes from outside the surface (its front)
  Frame frame;
  vec3 wo, woLocal;
  float alpha;      // GGX
  vec2 alphas;      // the anisotropic GGX's, along the frame's s and t
  float anisotropy; // ViewLayers::anisotropy: 0 where there is no stretch to orient
  float alphaCoat;  // the coat's GGX
  float pMirror;    // classic: the mirror's share of the samples
  float pSpecular;  // metallic-roughness: the GGX lobe's share
  float pSheen, pCoat, pTransmit;
  float alphaTransmit;  // the transmitted lobe's GGX
  // ViewLayers: the sheen's albedo and the scaling it leaves the base; the film's Fresnel.
  float sheenAlbedo, sheenScale;
  vec3 iridescenceF;
};

struct BsdfSample {
  vec3 wi;
  vec3 weight;  // f |cos| / pdf
  float pdf;    // 0 for the mirror's delta
  bool delta;
  bool transmitted;  // wi goes through the surface
};

float meanOf(vec3 c) {
  precise float m = (c.x + c.y + c.z) / 3.0;
  return m;
}

// A lobe choice u past a share p taken before it, rescaled to [0, 1) (pastShare).
float pastShare(float u, float p) {
  precise float r = (u - p) / (1.0 - p);
  return r;
}

Bsdf bsdfOf(RtMaterial m, bool metallicRoughness, vec3 n, vec3 wo, bool entering) {
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
  b.clearcoat = m.coatSheen.x;
  b.clearcoatRoughness = m.coatSheen.y;
  b.sheenRoughness = m.coatSheen.z;
  b.iridescence = m.coatSheen.w;
  b.sheenColor = m.sheenColorFilmIor.xyz;
  b.transmission = m.transmission.x;
  b.ior = m.transmission.y;
  b.thickness = m.transmission.z;
  b.entering = entering;
  b.frame = frameAbout(n);
  b.wo = wo;
  b.woLocal = toLocal(b.frame, wo);
  b.alpha = 1.0;
  b.alphas = vec2(1.0);
  b.anisotropy = 0.0;
  b.alphaCoat = 1.0;
  b.pMirror = 0.0;
  b.pSpecular = 0.0;
  b.pSheen = 0.0;
  b.pCoat = 0.0;
  b.pTransmit = 0.0;
  b.alphaTransmit = 1.0;
  b.sheenAlbedo = 0.0;
  b.sheenScale = 1.0;
  b.iridescenceF = vec3(0.0);
  if (!metallicRoughness) {
    // Bsdf::classic: samples follow each part's weight.
    precise float rest = b.diffuse * max(b.albedo.x, max(b.albedo.y, b.albedo.z)) + b.specular;
    float mirror = max(b.reflection, 0.0);
    precise float share = mirror / (mirror + rest);
    b.pMirror = mirror > 0.0 ? (rest > 0.0 ? share : 1.0) : 0.0;
    return b;
  }
  // Bsdf::metallicRoughness.
  b.alpha = ggxAlpha(b.roughness);
  float cosO = clamp(b.woLocal.z, 0.0, 1.0);
  ViewLayers view = rtViewLayers(m, n, cosO);
  if (view.anisotropy > 0.0) {
    // KHR_materials_anisotropy: the local frame's x along the stretch.
    b.frame = frameAlong(n, view.anisotropyT);
    b.woLocal = toLocal(b.frame, wo);
    b.anisotropy = view.anisotropy;
    // brdf.glsl's anisotropicAlpha with glm::mix's rounding, as the CPU's Bsdf gets it.
    precise float squared = b.anisotropy * b.anisotropy;
    b.alphas = vec2(mixAsGlm(b.alpha, 1.0, squared), b.alpha);
  }
  b.sheenAlbedo = view.sheenAlbedo;
  b.sheenScale = view.sheenScale;
  b.iridescenceF = view.iridescenceF;
  vec3 f0 = mix(b.dielectricF0, b.albedo, b.metallic);
  precise float f90 = b.dielectricF90 + (1.0 - b.dielectricF90) * b.metallic;
  float fresnel = meanOf(mixAsGlm(schlickFresnel90(f0, f90, cosO), b.iridescenceF, b.iridescence));
  precise float sheen = maxComponent(b.sheenColor) * b.sheenAlbedo;
  precise float specular = fresnel * b.sheenScale;
  precise float diffuse = meanOf(b.albedo) * (1.0 - b.metallic) * (1.0 - b.transmission) * (1.0 - fresnel) * b.sheenScale;
  precise float share = specular / (specular + diffuse);
  b.pSpecular = diffuse > 0.0 ? clamp(share, 0.1, 0.9) : 1.0;
  if (sheen > 0.0) {
    precise float under = specular + diffuse;
    precise float sheenShare = sheen / (sheen + under);
    b.pSheen = under > 0.0 ? clamp(sheenShare, 0.1, 0.9) : 1.0;
  }
  // The coat reflects clearcoat Fc toward the eye and passes the rest on.
  precise float coat = b.clearcoat > 0.0 ? b.clearcoat * schlickFresnel(vec3(0.04), cosO).x : 0.0;
  if (b.clearcoat > 0.0) {
    precise float base = (1.0 - coat) * (specular + diffuse + sheen);
    b.alphaCoat = ggxAlpha(b.clearcoatRoughness);
    precise float coatShare = coat / (coat + base);
    b.pCoat = base > 0.0 ? clamp(coatShare, 0.1, 0.9) : 1.0;
  }
  if (b.transmission > 0.0 && b.metallic < 1.0) {
    precise float through =
        meanOf(b.albedo) * (1.0 - b.metallic) * b.transmission * (1.0 - fresnel) * (1.0 - coat) * b.sheenScale;
    precise float reflected = coat + (1.0 - coat) * (specular + diffuse + sheen);
    precise float throughShare = through / (through + reflected);
    b.pTransmit = reflected > 0.0 ? clamp(throughShare, 0.1, 0.9) : 1.0;
    // A thin wall blurs as much as its ior bends; a volume's facets refract at the
    // surface's own roughness.
    b.alphaTransmit = ggxAlpha(b.thickness > 0.0 ? b.roughness : transmissionRoughness(b.roughness, b.ior));
  }
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
                     b.frame.n, b.clearcoat, b.clearcoatRoughness, b.transmission, b.sheenColor, b.sheenRoughness, b.sheenScale,
                     b.frame.s, b.frame.t, b.anisotropy, b.iridescenceF, b.iridescence);
}

// Bsdf::pdf: the density sample() draws wi with through its non-delta lobes.
float bsdfPdf(Bsdf b, vec3 wi) {
  vec3 wiLocal = toLocal(b.frame, wi);
  if (wiLocal.z <= 0.0 || b.woLocal.z <= 0.0) return 0.0;
  if (!b.metallicRoughness) {
    precise float pdf = (1.0 - b.pMirror) * cosineHemispherePdf(wiLocal.z);
    return pdf;
  }
  float specular = b.anisotropy > 0.0 ? ggxAnisotropicReflectionPdf(b.woLocal, wiLocal, b.alphas)
                                      : ggxReflectionPdf(b.woLocal, wiLocal, b.alpha);
  precise float base = b.pSpecular * specular + (1.0 - b.pSpecular) * cosineHemispherePdf(wiLocal.z);
  if (b.pSheen > 0.0) {
    precise float withSheen = b.pSheen * uniformConePdf(0.0) + (1.0 - b.pSheen) * base;
    base = withSheen;
  }
  precise float reflected = b.pCoat <= 0.0 ? base : b.pCoat * ggxReflectionPdf(b.woLocal, wiLocal, b.alphaCoat) + (1.0 - b.pCoat) * base;
  precise float pdf = (1.0 - b.pTransmit) * reflected;
  return pdf;
}

// Bsdf::transmissionSample through the visible normal m: refracted into a volume (or
// mirrored by m inside, past the critical angle), or mirrored and turned through a
// thin wall; weighed by what the layered model passes, times G1 of the new direction,
// over the lobe's share.
bool transmissionSample(Bsdf b, vec3 m, inout BsdfSample s) {
  float cosO = rtDot(b.woLocal, m);
  if (!(cosO > 0.0)) return false;
  vec3 fresnel = schlickFresnel90(b.dielectricF0, b.dielectricF90, cosO);
  precise vec3 share = (vec3(1.0) - fresnel) * b.albedo * ((1.0 - b.metallic) * b.transmission * b.sheenScale);
  vec3 wiLocal;
  if (b.thickness > 0.0) {
    float eta = b.entering ? 1.0 / max(b.ior, 1.0) : max(b.ior, 1.0);
    wiLocal = refractAsGlm(-b.woLocal, m, eta);
    if (wiLocal == vec3(0.0)) {
      // Total internal reflection: what the reflection lobe's Fresnel did not take
      // stays inside as well.
      wiLocal = reflectAbout(b.woLocal, m);
      if (wiLocal.z <= 0.0) return false;
    } else if (wiLocal.z >= 0.0) {
      return false;
    }
  } else {
    wiLocal = reflectAbout(b.woLocal, m);
    if (wiLocal.z <= 0.0) return false;
    wiLocal.z = -wiLocal.z;
  }
  s.wi = rtNormalize(toWorld(b.frame, wiLocal));
  precise vec3 weight = share * (ggxSmithG1(abs(wiLocal.z), b.alphaTransmit) / b.pTransmit);
  s.weight = weight;
  s.delta = true;
  s.transmitted = wiLocal.z < 0.0;
  return true;
}

// Bsdf::sample with its mirror, lambertSample and reflectionSample; false when it
// draws nothing.
bool bsdfSample(Bsdf b, vec2 u, float uLobe, out BsdfSample s) {
  s.wi = vec3(0.0, 0.0, 1.0);
  s.weight = vec3(0.0);
  s.pdf = 0.0;
  s.delta = false;
  s.transmitted = false;
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
  // Through the surface with the transmission's share; else reflectionSample with
  // uLobe rescaled past it: the coat, the sheen, the GGX lobe or the diffuse one, each
  // past the shares before it. One call site for the three GGX lobes' visible normals
  // (llvmpipe inlines every call).
  float rest = pastShare(uLobe, b.pTransmit);
  float pastCoat = pastShare(rest, b.pCoat);
  int lobe = uLobe < b.pTransmit                         ? 4
             : !b.metallicRoughness                      ? 3
             : rest < b.pCoat                            ? 0
             : pastCoat < b.pSheen                       ? 1
             : pastShare(pastCoat, b.pSheen) < b.pSpecular ? 2
                                                         : 3;
  vec3 h = vec3(0.0, 0.0, 1.0);
  if (lobe == 0 || lobe == 2 || lobe == 4) {
    vec2 alpha = lobe == 0 ? vec2(b.alphaCoat) : lobe == 2 ? (b.anisotropy > 0.0 ? b.alphas : vec2(b.alpha)) : vec2(b.alphaTransmit);
    h = sampleGgxAnisotropicVisibleNormal(b.woLocal, alpha, u);
  }
  if (lobe == 4) return transmissionSample(b, h, s);
  vec3 wiLocal;
  if (lobe == 1) {
    wiLocal = sampleUniformCone(u, 0.0);
  } else if (lobe == 3) {
    wiLocal = sampleCosineHemisphere(u);
  } else {
    wiLocal = reflectAbout(b.woLocal, h);
  }
  if (wiLocal.z <= 0.0) return false;
  s.wi = rtNormalize(toWorld(b.frame, wiLocal));
  s.pdf = bsdfPdf(b, s.wi);
  if (!(s.pdf > 0.0)) return false;
  s.weight = bsdfF(b, s.wi) * (rtDot(b.frame.n, s.wi) / s.pdf);
  return true;
}
