// glTF's textures at a tracer's hit, written once: the base colour, metallic-
// roughness and emissive texels, the layers' and the anisotropy's orientation. The CPU tracers
// (raytrace/rt_materials.cpp, through core/layer_texels.h) and the GPU tracers
// (rt/material_at.glsl) make a hit's material with this text; each fetches the
// texels its own way.
// tests/core/shading_texts_test.cpp runs it on the GPU's compiler against the C++
// build, case by case. The rasterizer applies its layer texels with this text too
// (common/material.glsl's materialLayers).
//
// In the subset of the two languages that common/sampling.glsl keeps to, after
// common/brdf.glsl; mixAsGlm is glm's mix.

// The film's thickness between its range's ends: glm's mix (mixAsGlm) in the
// tracers; the rasterizer takes GLSL's, which its goldens were made with.
#ifndef LAYER_MIX
#define LAYER_MIX mixAsGlm
#endif

// A hit's base values: the material's factors before its texels, the hit's after.
struct BaseValues {
  vec3 albedo;
  float metallic, roughness;
  vec3 emission;
};

// glTF's base colour times COLOR_0 (`vertexColor`) and times its texel's RGB; the
// roughness times the metallic-roughness texel's G, the metallic times its B; the
// emission times its texel's RGB. `texel` and `present`: base colour,
// metallic-roughness, emissive.
BRDF_INLINE BaseValues withBaseTexels(BaseValues v, vec3 vertexColor, vec4 texel[3], bool present[3]) {
  v.albedo = v.albedo * vertexColor;
  if (present[0]) v.albedo = v.albedo * vec3(texel[0].x, texel[0].y, texel[0].z);
  if (present[1]) {
    v.roughness = v.roughness * texel[1].y;
    v.metallic = v.metallic * texel[1].z;
  }
  if (present[2]) v.emission = v.emission * vec3(texel[2].x, texel[2].y, texel[2].z);
  return v;
}

// The 12 layer slots, TextureSlot's order from TextureSlot::Specular
// (asset/model_data.h); slot 6, the coat's normal map, is read where normals are.
#define LAYER_SLOTS 12

// A hit's layer values, the material's factors before its texels and the hit's
// after them.
struct LayerValues {
  vec3 specularColor;  // KHR_materials_specular's colour and weight: what tint the
  float specularWeight;  // dielectric's f0 (layerF0) and are its f90
  float clearcoat, clearcoatRoughness;
  float transmission, thickness;
  vec3 sheenColor;
  float sheenRoughness;
  vec2 anisotropyDirection;  // in the tangent frame: +x, or its texture's RG
  float anisotropy;          // the stretch's strength
  float iridescence, iridescenceThickness;
};

// Each present slot's texel applied, each from the channel glTF reads it in: the
// specular weight from A, its colour from RGB; the coat from R, its roughness from
// G; transmission from R, the volume's thickness from G; the sheen's colour from
// RGB, its roughness from A; the anisotropy's direction from RG (as [-1, 1]), its
// strength times B; the film from R, its thickness from G between `filmRange`'s
// two ends (nm).
BRDF_INLINE LayerValues withLayerTexels(LayerValues v, vec4 texel[LAYER_SLOTS], bool present[LAYER_SLOTS],
                                        vec2 filmRange) {
  if (present[0]) v.specularWeight = v.specularWeight * texel[0].w;
  if (present[1]) v.specularColor = v.specularColor * vec3(texel[1].x, texel[1].y, texel[1].z);
  if (present[2]) v.clearcoat = v.clearcoat * texel[2].x;
  if (present[3]) v.clearcoatRoughness = v.clearcoatRoughness * texel[3].y;
  if (present[4]) v.transmission = v.transmission * texel[4].x;
  if (present[5]) v.thickness = v.thickness * texel[5].y;
  if (present[7]) v.sheenColor = v.sheenColor * vec3(texel[7].x, texel[7].y, texel[7].z);
  if (present[8]) v.sheenRoughness = v.sheenRoughness * texel[8].w;
  if (present[9]) {
    precise vec2 direction = vec2(texel[9].x, texel[9].y) * 2.0f - 1.0f;
    v.anisotropyDirection = direction;
    v.anisotropy = v.anisotropy * texel[9].z;
  }
  if (present[10]) v.iridescence = v.iridescence * texel[10].x;
  if (present[11]) v.iridescenceThickness = LAYER_MIX(filmRange.x, filmRange.y, texel[11].y);
  return v;
}

// The dielectric's f0 tinted by KHR_materials_specular (MaterialLayers::dielectricF0):
// ((ior - 1) / (ior + 1))^2 (`reflectance`, in double) times the colour, at most 1,
// times the weight, in double.
BRDF_INLINE vec3 layerF0(double reflectance, vec3 color, float weight) {
  precise dvec3 f0 = min(dvec3(reflectance) * dvec3(color), dvec3(1.0)) * double(weight);
  return vec3(f0);
}

// KHR_materials_anisotropy's stretch at a hit, in world space: the tangent frame of
// the triangle's uv gradient dpdu, dpdv (the tangent MikkTSpace builds, flat across
// the triangle and following the posed mesh; the rasterizer interpolates the file's
// or the loader's tangents instead), the material's direction in it turned by its
// rotation (brdf.glsl's anisotropyDirection, as the rasterizer turns it). xyz the
// unit direction, w the strength clamped to [0, 1]; all 0 where the gradient gives
// nothing to orient it by. glTF's bitangent points up the image, against dP/dv (uv's
// v runs down it; its normal maps are +Y up): the files' TANGENT handedness says the
// same (RasterVsRaytrace.GltfAnisotropyAgrees turns on it).
BRDF_INLINE vec4 orientedAnisotropy(vec2 direction, float rotation, float strength, vec3 ns, vec3 dpdu, vec3 dpdv) {
  precise vec3 t = dpdu - ns * rtDot(ns, dpdu);
  float len = sqrt(rtDot(t, t));
  vec2 d = anisotropyDirection(direction, rotation);
  if (len > 0.0f && !isinf(len) && !isnan(len)) {
    vec3 tangent = t / len;
    vec3 across = rtCross(ns, tangent);
    vec3 b = rtDot(across, dpdv) < 0.0f ? across : -across;
    precise vec3 stretched = tangent * d.x + b * d.y;
    float slen = sqrt(rtDot(stretched, stretched));
    if (slen > 1e-6f) {
      vec3 unit = stretched / slen;
      return vec4(unit.x, unit.y, unit.z, clamp(strength, 0.0f, 1.0f));
    }
  }
  return vec4(0.0f);
}
