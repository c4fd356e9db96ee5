// RtScene::materialAt on the GPU (raytrace/rt_scene.cpp): a hit's material, its
// vertex colour and, built with RT_TEXTURES, its textures applied at the hit's uv with the ray cone's footprint (rt/texture.glsl):
// the base colour's, metallic-roughness's (roughness times G, metallic times B), the
// emissive one's, glTF's layers' and the terrain's layered material (raytrace/terrain_material.cpp;
// the blend is common/terrain_layers.glsl), operation for operation. Change both together. After
// rt/surface.glsl and rt/texture.glsl.

// A hit's texture reads at most: base colour, metallic-roughness, emissive, glTF's 12
// layer slots, the terrain's five.
#define RT_MOST_READS 20

#include "common/layer_texels.glsl"
#include "common/terrain_layers.glsl"

// RtTerrainMaterial::sample into the material from its five reads (grass near and
// far, rock near and far, snow): its albedo times the layers' blend
// (common/terrain_layers.glsl, the CPU's and the rasterizer's text), their roughness
// and highlight.
void rtApplyTerrain(inout RtMaterial m, vec4 reads[RT_MOST_READS], int first, double y, float normalY) {
  precise float height01 = float(y - m.terrainOriginYHeightScale.x) / float(m.terrainOriginYHeightScale.y);
  TerrainLayers t = terrainLayersOf(reads[first].xyz, reads[first + 1].xyz, reads[first + 2].xyz,
                                    reads[first + 3].xyz, reads[first + 4].xyz, height01, 1.0 - normalY);
  m.colorAmbient.xyz = m.colorAmbient.xyz * t.albedo;
  m.metallicRoughnessUnlit.y = t.roughness;
  m.diffuseSpecularShininessReflection.y = t.specular;
}

// The ray cone's footprint at the hit (raytrace/ray_cone.h's footprintAt): the cone
// widened over `distance`, stretched by 1 / cos along the slope, in uv units.
float rtFootprint(inout float coneWidth, float coneSpread, Surface s, vec3 v, float distance) {
  precise float width = coneWidth + coneSpread * distance;
  coneWidth = width;
  float cosine = max(abs(rtDot(s.n, v)), 1e-2);
  precise float footprint = width / cosine * s.uvPerMetre;
  return footprint;
}

// RtMaterials::applyLayerTextures, by the tracers' one text (common/layer_texels.glsl):
// `read[k]` is the texel of layer slot k (TextureSlot::Specular + k), or -1.
void rtApplyLayerTextures(inout RtMaterial m, vec4 texel[RT_MOST_READS], int read[12]) {
  vec4 layerTexel[LAYER_SLOTS];
  bool present[LAYER_SLOTS];
  for (int k = 0; k < LAYER_SLOTS; ++k) {
    present[k] = read[k] >= 0 && k != 6;  // the coat's normal map: the tracers read no normal maps
    layerTexel[k] = read[k] >= 0 ? texel[read[k]] : vec4(0.0);
  }
  LayerValues v;
  v.specularColor = m.specularLayer.xyz;
  v.specularWeight = m.specularLayer.w;
  v.clearcoat = m.coatSheen.x;
  v.clearcoatRoughness = m.coatSheen.y;
  v.transmission = m.transmission.x;
  v.thickness = m.transmission.z;
  v.sheenColor = m.sheenColorFilmIor.xyz;
  v.sheenRoughness = m.coatSheen.z;
  v.anisotropyDirection = m.anisotropy.zw;
  v.anisotropy = m.anisotropy.x;
  v.iridescence = m.coatSheen.w;
  v.iridescenceThickness = m.film.x;
  v = withLayerTexels(v, layerTexel, present, m.filmRange.xy);
  if (present[0] || present[1]) m.dielectric = vec4(layerF0(m.reflectance.x, v.specularColor, v.specularWeight), v.specularWeight);
  m.coatSheen = vec4(v.clearcoat, v.clearcoatRoughness, v.sheenRoughness, v.iridescence);
  m.transmission.x = v.transmission;
  m.transmission.z = v.thickness;
  m.sheenColorFilmIor.xyz = v.sheenColor;
  m.anisotropy.zw = v.anisotropyDirection;
  m.anisotropy.x = v.anisotropy;
  m.film.x = v.iridescenceThickness;
}

// The material at the hit (the unflipped shading normal's y for the terrain), built
// with RT_TEXTURES where some material reads a texture or is the terrain's. Its
// texture reads are listed first and made in one loop: llvmpipe inlines every call,
// and a sampler for each read made a kernel take 12 s to compile.
RtMaterial rtMaterialAt(Surface s, float footprint) {
  RtMaterial m = rtMaterials[s.material];
  vec4 baseTexel[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  bool basePresent[3] = bool[3](false, false, false);
#ifdef RT_TEXTURES
  ivec4 t = m.textures;
  int texture[RT_MOST_READS];
  vec2 uv[RT_MOST_READS];
  float width[RT_MOST_READS];
  int reads = 0;
  for (int k = 0; k < 3; ++k) {
    if (t[k] < 0) continue;
    texture[reads] = t[k];
    uv[reads] = s.uv0;
    width[reads++] = footprint;
  }
  int layerRead[12];
  for (int k = 0; k < 12; ++k) {
    int index = m.layerTextures[k / 4][k % 4];
    layerRead[k] = index >= 0 ? reads : -1;
    if (index < 0) continue;
    texture[reads] = index;
    uv[reads] = s.uv0;
    width[reads++] = footprint;
  }
  if (t.w >= 0) {
    precise vec2 uvFar = s.uv0 * TERRAIN_FAR_LAYER_SCALE;
    precise float footprintFar = footprint * TERRAIN_FAR_LAYER_SCALE;
    for (int k = 0; k < 5; ++k) {
      texture[reads + k] = m.terrainLayers[k / 2];
      uv[reads + k] = k % 2 == 0 ? s.uv0 : uvFar;
      width[reads + k] = k % 2 == 0 ? footprint : footprintFar;
    }
  }
  int terrainReads = t.w >= 0 ? 5 : 0;
  vec4 texel[RT_MOST_READS];
  for (int k = 0; k < reads + terrainReads; ++k) {
    // A material's textures read their own uv set (uv[k] stands for TEXCOORD_0 only
    // where the texture says so); the terrain's layers have one.
    texel[k] = rtSampleTexture(texture[k], uv[k], k < reads ? s.uv1 : uv[k], width[k]);
  }
  int next = 0;
  for (int k = 0; k < 3; ++k) {
    basePresent[k] = t[k] >= 0;
    if (basePresent[k]) baseTexel[k] = texel[next++];
  }
#endif
  // The base colour (times COLOR_0), metallic-roughness and emissive texels, by the
  // tracers' one text (common/layer_texels.glsl).
  BaseValues base;
  base.albedo = m.colorAmbient.xyz;
  base.metallic = m.metallicRoughnessUnlit.x;
  base.roughness = m.metallicRoughnessUnlit.y;
  base.emission = m.emission.xyz;
  base = withBaseTexels(base, s.color.xyz, baseTexel, basePresent);
  m.colorAmbient.xyz = base.albedo;
  m.metallicRoughnessUnlit.x = base.metallic;
  m.metallicRoughnessUnlit.y = base.roughness;
  m.emission.xyz = base.emission;
#ifdef RT_TEXTURES
  rtApplyLayerTextures(m, texel, layerRead);
  if (t.w >= 0) rtApplyTerrain(m, texel, reads, double(s.p.y), s.ns.y);
#endif
  // The stretch in world space (common/layer_texels.glsl, the CPU's text too).
  m.anisotropy = m.anisotropy.x > 0.0
                     ? orientedAnisotropy(m.anisotropy.zw, m.anisotropy.y, m.anisotropy.x, s.ns, s.dpdu, s.dpdv)
                     : vec4(0.0);
  return m;
}

// ---- Alpha and single-sided faces (RtScene::opacityAt, surfaceOpacity, transmittance) ----

// How much of a ray the surface stops: 1 opaque, MASK's 0 or 1 at its cutoff, or
// BLEND's alpha (the factor times COLOR_0's alpha times the base colour texture's).
float rtOpacity(Surface s, float footprint) {
  RtMaterial m = rtMaterials[s.material];
  int mode = int(m.alpha.x);
  if (mode == 0) return 1.0;
  float alpha = m.alpha.y * s.color.a;
#ifdef RT_TEXTURES
  if (m.textures.x >= 0) alpha = alpha * rtSampleTexture(m.textures.x, s.uv0, s.uv1, footprint).w;
#endif
  if (mode == 1) return alpha >= m.alpha.z ? 1.0 : 0.0;
  return clamp(alpha, 0.0, 1.0);
}

// rtOpacity, and 0 for a single-sided face seen from behind (the rasterizer culls it).
float rtSurfaceOpacity(Surface s, float footprint, bool backFacing) {
  return backFacing && rtMaterials[s.material].alpha.w != 0.0 ? 0.0 : rtOpacity(s, footprint);
}

// The share of light a shadow ray from o brings: along d up to tMax, or to `target`
// (d = target - o, tMax 1, spawnRayTo) when toTarget. An any-hit ray where every
// material is opaque; with RT_TRANSPARENT (some material is not) the product of
// 1 - opacity over the surfaces it passes, at the full-resolution level, as the CPU
// (each surface passed is one more ray in `rays`). The only shadow-ray call site of
// a kernel that includes it: llvmpipe inlines every traversal.
float rtTransmittance(vec3 o, vec3 d, float tMax, bool toTarget, vec3 target, inout uint rays) {
  ++rays;
#ifndef RT_TRANSPARENT
  return rtAnyHit(o, d, tMax) ? 0.0 : 1.0;
#else
  float share = 1.0;
  for (int i = 0; i <= 64; ++i) {
    RtHit hit = rtClosestHit(o, d, tMax);
    if (hit.kind == RT_NONE) return share;
    Surface s = surfaceAt(hit, o, d);
    share *= 1.0 - rtOpacity(s, 0.0);
    if (share <= 0.0) return 0.0;
    ++rays;
    if (toTarget) {
      o = offsetRayOrigin(s, target - s.p);
      precise vec3 toT = target - o;
      d = toT;
      tMax = 1.0;
    } else {
      o = offsetRayOrigin(s, d);
      precise float rest = tMax - hit.t;
      tMax = rest;
    }
  }
  return 0.0;
#endif
}
