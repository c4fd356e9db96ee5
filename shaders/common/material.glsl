// glTF 2.0 material inputs, shared by every program that draws glTF meshes
// (scene.frag, depth.frag). Each texture is compiled in only for the
// variants that use it (#defines set by engine/render/model_renderer.cpp):
//   TEXTURED          base colour texture (sRGB, UNIT_BASE_COLOR)
//   NORMAL_MAP        tangent-space normal map (linear, UNIT_NORMAL) with u_normalScale
//   MR_TEXTURE        metallic-roughness (linear, UNIT_METALLIC_ROUGHNESS): G roughness, B metallic
//   EMISSIVE_TEXTURE  emissive (sRGB, UNIT_EMISSIVE)
//   OCCLUSION         ambient occlusion (linear, UNIT_OCCLUSION): R, with u_occlusionStrength
//   ALPHA_MASK        discard below u_alphaCutoff
//   VERTEX_COLOR      the mesh's COLOR_0 multiplies the base colour (v_color)
//   MATERIAL_LAYERS   glTF's ior, specular and clear coat (common/shading.glsl), and
//   LAYER_TEXTURES    their textures (UNIT_SPECULAR ..., u_layerTextures says which)
//   CLEARCOAT_NORMAL  the coat's own normal map (UNIT_CLEARCOAT_NORMAL), with tangents
//   TRANSMISSION      KHR_materials_transmission and _volume (with MATERIAL_LAYERS;
//                     common/transmission.glsl draws what comes through)
//   SHEEN             KHR_materials_sheen (with MATERIAL_LAYERS; its textures with
//                     LAYER_TEXTURES, UNIT_SHEEN_COLOR and UNIT_SHEEN_ROUGHNESS)
//   ANISOTROPY        KHR_materials_anisotropy (with MATERIAL_LAYERS, on a mesh with
//                     tangents; its texture with LAYER_TEXTURES, UNIT_ANISOTROPY)
//   IRIDESCENCE       KHR_materials_iridescence (with MATERIAL_LAYERS; its textures
//                     with LAYER_TEXTURES, UNIT_IRIDESCENCE and _THICKNESS)
//   UV_TRANSFORM      some slot reads TEXCOORD_1 or has a KHR_texture_transform:
//                     every slot reads its set (u_texCoord) through its matrix
//                     (u_uvTransform, built in C++: asset/texture_transform.h)
// The units are engine/gl/bindings.h's. Each slot's glTF sampler (wrap, filters) is a
// sampler object bound on its unit.
//
// Without UV_TRANSFORM a slot samples TEXCOORD_0 as it is: models that use neither
// feature run the same programs as before. With it, each texture fetch costs a
// select and a mat3 multiply more; the variant is built only for such materials.

// The slots, as engine::TextureSlot numbers them (tests/gl/shader_source_test
// holds the two together).
const int SLOT_BASE_COLOR = 0;
const int SLOT_NORMAL = 1;
const int SLOT_METALLIC_ROUGHNESS = 2;
const int SLOT_EMISSIVE = 3;
const int SLOT_OCCLUSION = 4;
const int SLOT_SPECULAR = 5;
const int SLOT_SPECULAR_COLOR = 6;
const int SLOT_CLEARCOAT = 7;
const int SLOT_CLEARCOAT_ROUGHNESS = 8;
const int SLOT_TRANSMISSION = 9;
const int SLOT_THICKNESS = 10;
const int SLOT_CLEARCOAT_NORMAL = 11;
const int SLOT_SHEEN_COLOR = 12;
const int SLOT_SHEEN_ROUGHNESS = 13;
const int SLOT_ANISOTROPY = 14;
const int SLOT_IRIDESCENCE = 15;
const int SLOT_IRIDESCENCE_THICKNESS = 16;

#ifdef UV_TRANSFORM
in vec2 v_uv1;  // TEXCOORD_1 (set 0 where the mesh has none)
uniform mat3 u_uvTransform[17];
uniform int u_texCoord[17];
#endif

// The uv that `slot` samples at, from the fragment's TEXCOORD_0 `uv`.
vec2 materialUv(int slot, vec2 uv) {
#ifdef UV_TRANSFORM
  vec2 set = u_texCoord[slot] == 1 ? v_uv1 : uv;
  return (u_uvTransform[slot] * vec3(set, 1.0)).xy;
#else
  return uv;
#endif
}
#ifdef TEXTURED
layout(binding = UNIT_BASE_COLOR) uniform sampler2D u_baseColorTexture;
#endif
uniform vec4 u_baseColorFactor = vec4(1.0);
#ifdef SURFACE_IN
// Shaded from a surface (scene.frag's SURFACE_IN): the pixel's neighbours may be
// other triangles, so the base colour's level of detail is the one the surface pass
// found where the triangle's own derivatives were known. Only the base colour may
// be textured there (ShaderVariant::deferrable).
float g_baseColorLod;
#define BASE_COLOR_TEXEL(t, uv) textureLod(t, uv, g_baseColorLod)
#else
#define BASE_COLOR_TEXEL(t, uv) texture(t, uv)
#endif

#ifdef VERTEX_COLOR
in vec4 v_color;  // COLOR_0, linear RGBA
#endif

// glTF's base colour: the factor times the texture times the vertex colour.
vec4 materialBaseColor(vec2 uv) {
  vec4 color = u_baseColorFactor;
#ifdef TEXTURED
  color *= BASE_COLOR_TEXEL(u_baseColorTexture, materialUv(SLOT_BASE_COLOR, uv));
#endif
#ifdef VERTEX_COLOR
  color *= v_color;
#endif
  return color;
}

#ifdef ALPHA_MASK
uniform float u_alphaCutoff = 0.5;
#endif

// MASK: below the cutoff the fragment is not there (colour, depth and shadow).
void materialAlphaTest(float alpha) {
#ifdef ALPHA_MASK
  if (alpha < u_alphaCutoff) discard;
#endif
}

#if defined(NORMAL_MAP) || defined(CLEARCOAT_NORMAL)
// A tangent-space normal map's direction in world space. `n` is the interpolated
// vertex normal (unit), `tangent` the interpolated tangent with its handedness in
// w; the bitangent is cross(n, t) * w as glTF defines it. The tangent is made
// orthogonal to n again after interpolation; where it has collapsed the map is
// ignored. `texel` is the map's value at the fragment, xy scaled by `scale`.
vec3 perturbedNormal(vec3 n, vec4 tangent, vec3 texel, float scale) {
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  float len = length(t);
  if (!(len > 1e-6)) return n;
  t /= len;
  vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 m = texel * 2.0 - 1.0;
  m.xy *= scale;
  vec3 perturbed = mat3(t, b, n) * m;
  float plen = length(perturbed);
  return plen > 1e-6 ? perturbed / plen : n;
}
#endif

#ifdef NORMAL_MAP
layout(binding = UNIT_NORMAL) uniform sampler2D u_normalTexture;
uniform float u_normalScale = 1.0;

vec3 materialNormal(vec3 n, vec4 tangent, vec2 uv) {
  return perturbedNormal(n, tangent, texture(u_normalTexture, materialUv(SLOT_NORMAL, uv)).xyz, u_normalScale);
}
#endif

#ifdef CLEARCOAT_NORMAL
// KHR_materials_clearcoat's clearcoatNormalTexture: the coat's own normal.
layout(binding = UNIT_CLEARCOAT_NORMAL) uniform sampler2D u_clearcoatNormalTexture;
uniform float u_clearcoatNormalScale = 1.0;

vec3 materialClearcoatNormal(vec3 n, vec4 tangent, vec2 uv) {
  return perturbedNormal(n, tangent, texture(u_clearcoatNormalTexture, materialUv(SLOT_CLEARCOAT_NORMAL, uv)).xyz,
                         u_clearcoatNormalScale);
}
#endif

#ifdef MR_TEXTURE
layout(binding = UNIT_METALLIC_ROUGHNESS) uniform sampler2D u_metallicRoughnessTexture;
#endif

// x = metallic, y = roughness: the factors times the texture's B and G.
vec2 materialMetallicRoughness(float metallic, float roughness, vec2 uv) {
#ifdef MR_TEXTURE
  vec4 mr = texture(u_metallicRoughnessTexture, materialUv(SLOT_METALLIC_ROUGHNESS, uv));
  return vec2(metallic * mr.b, roughness * mr.g);
#else
  return vec2(metallic, roughness);
#endif
}

#ifdef EMISSIVE_TEXTURE
layout(binding = UNIT_EMISSIVE) uniform sampler2D u_emissiveTexture;
#endif

vec3 materialEmissive(vec3 factor, vec2 uv) {
#ifdef EMISSIVE_TEXTURE
  return factor * texture(u_emissiveTexture, materialUv(SLOT_EMISSIVE, uv)).rgb;
#else
  return factor;
#endif
}

#ifdef OCCLUSION
layout(binding = UNIT_OCCLUSION) uniform sampler2D u_occlusionTexture;
uniform float u_occlusionStrength = 1.0;
#endif

// The factor on the ambient term: 1 + strength * (R - 1), as glTF defines it.
float materialOcclusion(vec2 uv) {
#ifdef OCCLUSION
  return 1.0 + u_occlusionStrength * (texture(u_occlusionTexture, materialUv(SLOT_OCCLUSION, uv)).r - 1.0);
#else
  return 1.0;
#endif
}

#ifdef MATERIAL_LAYERS
// KHR_materials_ior, _specular, _clearcoat, _transmission, _volume, _sheen: the
// factors, times their textures where
// the material has them, into common/shading.glsl's g_ values for this fragment.
uniform float u_iorF0;          // ((ior - 1) / (ior + 1))^2
uniform float u_specularWeight;
uniform vec3 u_specularColor;
uniform float u_clearcoat;
uniform float u_clearcoatRoughness;
uniform float u_transmission;
uniform float u_thickness;  // in the mesh's units
uniform vec3 u_sheenColor;   // linear
uniform float u_sheenRoughness;
uniform float u_anisotropy;          // strength
uniform float u_anisotropyRotation;  // radians, from the tangent toward the bitangent
uniform float u_iridescence;
uniform vec2 u_iridescenceThickness;  // nm: the texture's G = 0 and 1 (the latter without one)
#ifdef LAYER_TEXTURES
layout(binding = UNIT_SPECULAR) uniform sampler2D u_specularTexture;              // A
layout(binding = UNIT_SPECULAR_COLOR) uniform sampler2D u_specularColorTexture;   // RGB, sRGB
layout(binding = UNIT_CLEARCOAT) uniform sampler2D u_clearcoatTexture;            // R
layout(binding = UNIT_CLEARCOAT_ROUGHNESS) uniform sampler2D u_clearcoatRoughnessTexture;  // G
layout(binding = UNIT_TRANSMISSION) uniform sampler2D u_transmissionTexture;  // R
layout(binding = UNIT_THICKNESS) uniform sampler2D u_thicknessTexture;        // G
#ifdef SHEEN
layout(binding = UNIT_SHEEN_COLOR) uniform sampler2D u_sheenColorTexture;          // RGB, sRGB
layout(binding = UNIT_SHEEN_ROUGHNESS) uniform sampler2D u_sheenRoughnessTexture;  // A
#endif
#ifdef ANISOTROPY
layout(binding = UNIT_ANISOTROPY) uniform sampler2D u_anisotropyTexture;  // RG direction, B strength
#endif
#ifdef IRIDESCENCE
layout(binding = UNIT_IRIDESCENCE) uniform sampler2D u_iridescenceTexture;                     // R
layout(binding = UNIT_IRIDESCENCE_THICKNESS) uniform sampler2D u_iridescenceThicknessTexture;  // G
#endif
uniform int u_layerTextures;  // bit (slot - SLOT_SPECULAR): the slot has a texture

bool hasLayerTexture(int slot) { return (u_layerTextures & (1 << (slot - SLOT_SPECULAR))) != 0; }
#endif

// The film's thickness between its range's two ends is GLSL's mix here (the
// goldens were made with it), glm's in the tracers (common/layer_texels.glsl).
#define LAYER_MIX mix
#include "rt/math.glsl"
#include "common/layer_texels.glsl"

#ifdef LAYER_TEXTURES
// Slot `slot`'s texel at uv where the material has a texture there.
void layerTexel(int slot, sampler2D tex, vec2 uv, inout vec4 texel[LAYER_SLOTS], inout bool present[LAYER_SLOTS]) {
  int k = slot - SLOT_SPECULAR;
  present[k] = hasLayerTexture(slot);
  if (present[k]) texel[k] = texture(tex, materialUv(slot, uv));
}
#endif

#ifdef ANISOTROPY
// The stretch's direction in the tangent frame and its strength, as materialLayers
// found them, for materialAnisotropy.
vec2 g_layerAnisotropyDirection;
float g_layerAnisotropy;
#endif

// The layers' factors times their texels, each from the channel glTF reads it in:
// the tracers' text (common/layer_texels.glsl's withLayerTexels), fetched here.
void materialLayers(vec2 uv) {
  LayerValues v;
  v.specularColor = u_specularColor;
  v.specularWeight = u_specularWeight;
  v.clearcoat = u_clearcoat;
  v.clearcoatRoughness = u_clearcoatRoughness;
  v.transmission = u_transmission;
  v.thickness = u_thickness;
  v.sheenColor = u_sheenColor;
  v.sheenRoughness = u_sheenRoughness;
  v.anisotropyDirection = vec2(1.0, 0.0);
  v.anisotropy = u_anisotropy;
  v.iridescence = u_iridescence;
  v.iridescenceThickness = u_iridescenceThickness.y;
  vec4 texel[LAYER_SLOTS];
  bool present[LAYER_SLOTS];
  for (int k = 0; k < LAYER_SLOTS; ++k) {
    texel[k] = vec4(0.0);
    present[k] = false;
  }
#ifdef LAYER_TEXTURES
  layerTexel(SLOT_SPECULAR, u_specularTexture, uv, texel, present);
  layerTexel(SLOT_SPECULAR_COLOR, u_specularColorTexture, uv, texel, present);
  layerTexel(SLOT_CLEARCOAT, u_clearcoatTexture, uv, texel, present);
  layerTexel(SLOT_CLEARCOAT_ROUGHNESS, u_clearcoatRoughnessTexture, uv, texel, present);
  layerTexel(SLOT_TRANSMISSION, u_transmissionTexture, uv, texel, present);
  layerTexel(SLOT_THICKNESS, u_thicknessTexture, uv, texel, present);
#ifdef SHEEN
  layerTexel(SLOT_SHEEN_COLOR, u_sheenColorTexture, uv, texel, present);
  layerTexel(SLOT_SHEEN_ROUGHNESS, u_sheenRoughnessTexture, uv, texel, present);
#endif
#ifdef ANISOTROPY
  layerTexel(SLOT_ANISOTROPY, u_anisotropyTexture, uv, texel, present);
#endif
#ifdef IRIDESCENCE
  layerTexel(SLOT_IRIDESCENCE, u_iridescenceTexture, uv, texel, present);
  layerTexel(SLOT_IRIDESCENCE_THICKNESS, u_iridescenceThicknessTexture, uv, texel, present);
#endif
#endif
  v = withLayerTexels(v, texel, present, u_iridescenceThickness);
  g_clearcoat = v.clearcoat;
  g_clearcoatRoughness = v.clearcoatRoughness;
  g_transmission = v.transmission;
  g_thickness = v.thickness;
#ifdef SHEEN
  g_sheenColor = v.sheenColor;
  g_sheenRoughness = v.sheenRoughness;
#endif
#ifdef IRIDESCENCE
  g_iridescence = v.iridescence;
  g_iridescenceThickness = v.iridescenceThickness;
#endif
#ifdef ANISOTROPY
  g_layerAnisotropyDirection = v.anisotropyDirection;
  g_layerAnisotropy = v.anisotropy;
#endif
  // In float, from the float reflectance (the tracers' layerF0 works in double).
  g_dielectricF0 = min(vec3(u_iorF0) * v.specularColor, vec3(1.0)) * v.specularWeight;
  g_dielectricF90 = v.specularWeight;
}
#endif

#ifdef ANISOTROPY
// KHR_materials_anisotropy: the stretch's direction in world space from the mesh's
// tangent frame (the interpolated normal `n`, `tangent` with its handedness), the
// texture's direction (or the tangent) turned by the rotation (common/brdf.glsl's
// anisotropyDirection), and its strength, into common/shading.glsl's g_ values. The
// direction across it is taken about the geometric normal `ng`, as the Sample
// Viewer does.
void materialAnisotropy(vec3 n, vec3 ng, vec4 tangent) {
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  float len = length(t);
  g_anisotropy = 0.0;
  if (!(len > 1e-6)) return;
  t /= len;
  vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
  float strength = g_layerAnisotropy;
  vec2 direction = anisotropyDirection(g_layerAnisotropyDirection, u_anisotropyRotation);
  vec3 stretched = t * direction.x + b * direction.y;
  float slen = length(stretched);
  if (!(slen > 1e-6)) return;
  g_anisotropyT = stretched / slen;
  g_anisotropyB = cross(ng, g_anisotropyT);
  g_anisotropy = clamp(strength, 0.0, 1.0);
}
#endif
