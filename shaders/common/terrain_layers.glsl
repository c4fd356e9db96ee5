// How the terrain's layers blend, written once: the rasterizer (common/
// terrain_material.glsl, for terrain.frag and terrain_deferred.frag), the GPU tracers
// (rt/material_at.glsl) and, through its C++ compile in engine/terrain/materials.h,
// the CPU tracers (raytrace/terrain_material.cpp) blend grass, rock and snow with
// this text. tests/core/shading_texts_test.cpp compares the GLSL compile with the C++ one.
//
// In the subset of the two languages that common/brdf.glsl keeps to; smoothstep, max,
// mix and dot are GLSL's on the GPU and glm's in C++ (no `precise`: the rasterizer's
// goldens were made with what its compiler makes of these lines).
#ifndef BRDF_INLINE
#define BRDF_INLINE
#endif

// Two scales of the same layer break up visible repetition: the far one's texture
// coordinates are the near one's times this.
const float TERRAIN_FAR_LAYER_SCALE = 0.173f;
// The classic highlight's exponent on every layer.
const float TERRAIN_LAYER_SHININESS = 24.0f;

// Layer weights (grass, rock, snow), summing to one, at height01 (metres above the
// terrain's origin over its height scale), `slope` (1 - n.y of the unit shading
// normal) and `jitter` (rock.r * 2 - 0.5 of the rock layer's linear colour): rock
// where steep, snow high up where it can lie (not on cliffs), grass elsewhere. The
// texture's own brightness jitters the snow line so it does not follow a contour.
BRDF_INLINE vec3 terrainLayerWeights(float height01, float slope, float jitter) {
  float rock = smoothstep(0.28f, 0.5f, slope);
  float snow = smoothstep(0.6f, 0.7f, height01 + 0.05f * jitter) * (1.0f - smoothstep(0.35f, 0.6f, slope));
  float grass = max(1.0f - rock - snow, 0.0f);
  return vec3(grass, rock, snow) / max(grass + rock + snow, 1e-4f);
}

struct TerrainLayers {
  vec3 albedo;      // linear
  float roughness;  // rough dielectrics; snow a little glossier
  float specular;   // the classic highlight's weight: faint, on snow
};

// From the layers' reads (linear colours: grass and rock at the near and the far
// scale, snow at the near one), height01 and slope as terrainLayerWeights takes them.
BRDF_INLINE TerrainLayers terrainLayersOf(vec3 grassNear, vec3 grassFar, vec3 rockNear, vec3 rockFar, vec3 snow,
                                          float height01, float slope) {
  vec3 grass = grassNear * grassFar * 2.0f;
  vec3 rock = rockNear * rockFar * 2.0f;
  vec3 w = terrainLayerWeights(height01, slope, rock.x * 2.0f - 0.5f);
  TerrainLayers t;
  t.albedo = grass * w.x + rock * w.y + snow * w.z;
  t.roughness = dot(w, vec3(0.95f, 0.8f, 0.5f));
  t.specular = mix(0.02f, 0.25f, w.z);
  return t;
}
