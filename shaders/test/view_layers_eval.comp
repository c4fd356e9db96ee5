#version 450 core
// tests/core/shading_texts_test.cpp: the view's terms of glTF's layers
// (common/view_layers.glsl) on the GPU's compiler, for random inputs, so that the C++
// build of the same text (core/view_layers.h) can be compared case by case.
#include "rt/math.glsl"
#include "common/brdf.glsl"
#include "common/view_layers.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 n;         // xyz: a unit normal; w: N.V
  vec4 sheen;     // xyz: the sheen's colour; w: its albedo E
  vec4 stretch;   // xyz: the anisotropy's direction in the world; w: its strength
  vec4 film;      // share, ior, thickness (nm); w: metallic
  vec4 f0;        // xyz: the dielectric's f0
  vec4 albedo;    // xyz
};

struct Result {
  vec4 anisotropyT;  // w: anisotropy
  vec4 anisotropyB;  // w: sheenScale
  vec4 iridescenceF; // w: sheenAlbedo
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  ViewLayers v = viewLayersOf(c.n.xyz, c.n.w, c.sheen.w, c.sheen.xyz, c.stretch.xyz, c.stretch.w, c.film.x, c.film.y,
                              c.film.z, c.f0.xyz, c.albedo.xyz, c.film.w);
  Result r;
  r.anisotropyT = vec4(v.anisotropyT, v.anisotropy);
  r.anisotropyB = vec4(v.anisotropyB, v.sheenScale);
  r.iridescenceF = vec4(v.iridescenceF, v.sheenAlbedo);
  results[i] = r;
}
