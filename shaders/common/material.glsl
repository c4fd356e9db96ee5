// glTF 2.0 material inputs, shared by every program that draws glTF meshes
// (scene.frag, lit.frag, depth.frag). Each texture is compiled in only for the
// variants that use it (#defines set by engine/render/model_renderer.cpp):
//   TEXTURED          base colour texture (sRGB, unit 0)
//   NORMAL_MAP        tangent-space normal map (linear, unit 1) with u_normalScale
//   MR_TEXTURE        metallic-roughness (linear, unit 2): G roughness, B metallic
//   EMISSIVE_TEXTURE  emissive (sRGB, unit 3)
//   OCCLUSION         ambient occlusion (linear, unit 6): R, with u_occlusionStrength
//   ALPHA_MASK        discard below u_alphaCutoff
// Units 4 and 5 are the shadow maps.
#ifdef TEXTURED
layout(binding = UNIT_BASE_COLOR) uniform sampler2D u_baseColorTexture;
#endif
uniform vec4 u_baseColorFactor = vec4(1.0);

vec4 materialBaseColor(vec2 uv) {
#ifdef TEXTURED
  return u_baseColorFactor * texture(u_baseColorTexture, uv);
#else
  return u_baseColorFactor;
#endif
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

#ifdef NORMAL_MAP
layout(binding = UNIT_NORMAL) uniform sampler2D u_normalTexture;
uniform float u_normalScale = 1.0;

// The normal map's direction in world space. `n` is the interpolated vertex
// normal (unit), `tangent` the interpolated tangent with its handedness in w; the
// bitangent is cross(n, t) * w as glTF defines it. The tangent is made orthogonal
// to n again after interpolation; where it has collapsed the map is ignored.
vec3 materialNormal(vec3 n, vec4 tangent, vec2 uv) {
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  float len = length(t);
  if (!(len > 1e-6)) return n;
  t /= len;
  vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 m = texture(u_normalTexture, uv).xyz * 2.0 - 1.0;
  m.xy *= u_normalScale;
  vec3 perturbed = mat3(t, b, n) * m;
  float plen = length(perturbed);
  return plen > 1e-6 ? perturbed / plen : n;
}
#endif

#ifdef MR_TEXTURE
layout(binding = UNIT_METALLIC_ROUGHNESS) uniform sampler2D u_metallicRoughnessTexture;
#endif

// x = metallic, y = roughness: the factors times the texture's B and G.
vec2 materialMetallicRoughness(float metallic, float roughness, vec2 uv) {
#ifdef MR_TEXTURE
  vec4 mr = texture(u_metallicRoughnessTexture, uv);
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
  return factor * texture(u_emissiveTexture, uv).rgb;
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
  return 1.0 + u_occlusionStrength * (texture(u_occlusionTexture, uv).r - 1.0);
#else
  return 1.0;
#endif
}
