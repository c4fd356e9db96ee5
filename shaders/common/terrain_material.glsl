// The terrain's surface: grass, rock and snow blended by height and slope, lit with
// the same frame block, lighting model (common/shading.glsl), sun and point shadows
// and fog as scene.frag, so a rock and the ground beside it agree. Shared by
// terrain.frag (shaded where drawn) and terrain_deferred.frag (shaded once a pixel
// from the surface terrain.frag's TERRAIN_SURFACE variant left). TERRAIN_LAYER(t, uv,
// lod) reads a layer texture: with the implicit level of detail where drawn, at the
// level stored with the surface in the deferred pass.
#include "common/frame.glsl"
#include "common/shading.glsl"
#include "common/shadows.glsl"
#include "common/direct_light.glsl"
#include "common/fog.glsl"
#include "common/output.glsl"

layout(binding = UNIT_TERRAIN_LAYERS) uniform sampler2D u_grassTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 1) uniform sampler2D u_rockTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 2) uniform sampler2D u_snowTexture;
uniform float u_heightScale;

// Two scales of the same layer break up visible repetition: the far one's texture
// coordinates are the near one's times this.
const float kFarLayerScale = 0.173;

// Layer weights, summing to one: rock where steep, snow high up where it can lie
// (not on cliffs), grass elsewhere. The texture's own brightness jitters the snow
// line so it does not follow a contour exactly. The ray tracer's twin is
// engine::terrain::layerWeights (engine/terrain/materials.cpp), which also holds
// terrainColor's scales, roughness and highlight below (materials.h): change both
// together.
vec3 layerWeights(float height01, float slope, float jitter) {
  float rock = smoothstep(0.28, 0.5, slope);
  float snow = smoothstep(0.6, 0.7, height01 + 0.05 * jitter) * (1.0 - smoothstep(0.35, 0.6, slope));
  float grass = max(1.0 - rock - snow, 0.0);
  return vec3(grass, rock, snow) / max(grass + rock + snow, 1e-4);
}

// position: camera-relative world; n: unit normal; height: metres above the
// terrain's origin; uv: the near layer scale's coordinates; lod: the near and far
// scales' texture levels of detail (TERRAIN_LAYER's third argument).
vec3 terrainColor(vec3 position, vec3 n, float height, vec2 uv, vec2 lod) {
  vec3 toEye = normalize(-position);  // the camera sits at the origin
  vec2 uvFar = uv * kFarLayerScale;
  vec3 grass = TERRAIN_LAYER(u_grassTexture, uv, lod.x).rgb * TERRAIN_LAYER(u_grassTexture, uvFar, lod.y).rgb * 2.0;
  vec3 rock = TERRAIN_LAYER(u_rockTexture, uv, lod.x).rgb * TERRAIN_LAYER(u_rockTexture, uvFar, lod.y).rgb * 2.0;
  vec3 snow = TERRAIN_LAYER(u_snowTexture, uv, lod.x).rgb;
  vec3 w = layerWeights(height / u_heightScale, 1.0 - n.y, rock.r * 2.0 - 0.5);
  vec3 albedo = grass * w.x + rock * w.y + snow * w.z;
  // Rough dielectrics; snow a little glossier. Classic weights: the scene's ambient
  // (frame block), full diffuse, a faint highlight on snow.
  float roughness = dot(w, vec3(0.95, 0.8, 0.5));
  float specular = mix(0.02, 0.25, w.z);
  Surface s = Surface(albedo, n, toEye, position, 0.0, roughness, u_ambientSky.w, 1.0, specular, 24.0, 0.0);
  vec3 color = shadeAmbient(s) + shadeDirectLight(s, n);
#ifdef FOG
  color = applyFog(color, length(position), u_fog.rgb, u_fog.w);
#endif
  return color;
}
