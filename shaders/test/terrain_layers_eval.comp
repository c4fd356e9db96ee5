#version 450 core
// tests/core/shading_texts_test.cpp: the terrain's layer blend (common/terrain_layers.glsl)
// on the GPU's compiler, for random inputs, so that the C++ build of the same text
// (terrain/materials.h) can be compared case by case.
#include "common/terrain_layers.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 grassNear, grassFar, rockNear, rockFar;  // xyz: linear colours
  vec4 snow;                                    // xyz: linear colour; w: height01
  vec4 slope;                                   // x: 1 - n.y
};
struct Result {
  vec4 albedo;  // w: roughness
  vec4 weights; // xyz: terrainLayerWeights at the rock's jitter; w: specular
};

layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { Result results[]; };
uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Case c = cases[i];
  TerrainLayers t = terrainLayersOf(c.grassNear.xyz, c.grassFar.xyz, c.rockNear.xyz, c.rockFar.xyz, c.snow.xyz,
                                    c.snow.w, c.slope.x);
  vec3 rock = c.rockNear.xyz * c.rockFar.xyz * 2.0;
  Result r;
  r.albedo = vec4(t.albedo, t.roughness);
  r.weights = vec4(terrainLayerWeights(c.snow.w, c.slope.x, rock.x * 2.0 - 0.5), t.specular);
  results[i] = r;
}
