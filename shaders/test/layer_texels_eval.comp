#version 450 core
// tests/core/shading_texts_test.cpp: glTF's layer texels at a hit
// (common/layer_texels.glsl) on the GPU's compiler, for random inputs, so that the
// C++ build of the same text (core/layer_texels.h) can be compared case by case.
#include "rt/math.glsl"
#include "common/brdf.glsl"
#include "common/layer_texels.glsl"

layout(local_size_x = 64) in;

struct Case {
  dvec4 reflectance;  // x; first, so that C++'s struct has std430's offsets
  vec4 texel[LAYER_SLOTS];
  vec4 specular;      // xyz: the colour; w: the weight
  vec4 coat;          // clearcoat, its roughness, transmission, thickness
  vec4 sheen;         // xyz: the colour; w: its roughness
  vec4 anisotropy;    // xy: the direction; z: the strength; w: iridescence
  vec4 film;          // x: its thickness; yz: the range; w: the present slots' bits
  vec4 pad;           // the array's stride a multiple of dvec4's 32 bytes
};
struct Result {
  vec4 specular, coat, sheen, anisotropy, film;  // as the case's, after the texels
  vec4 f0;                                       // xyz: layerF0
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  LayerValues v;
  v.specularColor = c.specular.xyz;
  v.specularWeight = c.specular.w;
  v.clearcoat = c.coat.x;
  v.clearcoatRoughness = c.coat.y;
  v.transmission = c.coat.z;
  v.thickness = c.coat.w;
  v.sheenColor = c.sheen.xyz;
  v.sheenRoughness = c.sheen.w;
  v.anisotropyDirection = c.anisotropy.xy;
  v.anisotropy = c.anisotropy.z;
  v.iridescence = c.anisotropy.w;
  v.iridescenceThickness = c.film.x;
  bool present[LAYER_SLOTS];
  uint bits = floatBitsToUint(c.film.w);
  for (int k = 0; k < LAYER_SLOTS; ++k) present[k] = (bits & (1u << k)) != 0u;
  v = withLayerTexels(v, c.texel, present, c.film.yz);
  Result r;
  r.specular = vec4(v.specularColor, v.specularWeight);
  r.coat = vec4(v.clearcoat, v.clearcoatRoughness, v.transmission, v.thickness);
  r.sheen = vec4(v.sheenColor, v.sheenRoughness);
  r.anisotropy = vec4(v.anisotropyDirection, v.anisotropy, v.iridescence);
  r.film = vec4(v.iridescenceThickness, 0.0, 0.0, 0.0);
  r.f0 = vec4(layerF0(c.reflectance.x, v.specularColor, v.specularWeight), 0.0);
  results[i] = r;
}
