// The terrain's surface: grass, rock and snow blended by height and slope
// (common/terrain_layers.glsl, the tracers' text too), lit with
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
#ifdef AERIAL_PERSPECTIVE
#include "common/aerial_perspective.glsl"
#endif
#include "common/output.glsl"
#include "common/terrain_layers.glsl"

layout(binding = UNIT_TERRAIN_LAYERS) uniform sampler2D u_grassTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 1) uniform sampler2D u_rockTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 2) uniform sampler2D u_snowTexture;
uniform float u_heightScale;

// position: camera-relative world; n: unit normal; height: metres above the
// terrain's origin; uv: the near layer scale's coordinates; lod: the near and far
// scales' texture levels of detail (TERRAIN_LAYER's third argument).
vec3 terrainColor(vec3 position, vec3 n, float height, vec2 uv, vec2 lod) {
  vec3 toEye = normalize(-position);  // the camera sits at the origin
  vec2 uvFar = uv * TERRAIN_FAR_LAYER_SCALE;
  TerrainLayers t = terrainLayersOf(
      TERRAIN_LAYER(u_grassTexture, uv, lod.x).rgb, TERRAIN_LAYER(u_grassTexture, uvFar, lod.y).rgb,
      TERRAIN_LAYER(u_rockTexture, uv, lod.x).rgb, TERRAIN_LAYER(u_rockTexture, uvFar, lod.y).rgb,
      TERRAIN_LAYER(u_snowTexture, uv, lod.x).rgb, height / u_heightScale, 1.0 - n.y);
  // Classic weights: the scene's ambient (frame block), full diffuse, the layers' highlight.
  Surface s = Surface(t.albedo, n, toEye, position, 0.0, t.roughness, u_ambientSky.w, 1.0, t.specular,
                      TERRAIN_LAYER_SHININESS, 0.0);
  vec3 color = shadeAmbient(s) + shadeDirectLight(s, n);
#ifdef FOG
  color = applyFog(color, length(position), u_fog.rgb, u_fog.w);
#endif
#ifdef AERIAL_PERSPECTIVE
  color = applyAerialPerspective(color, position);
#endif
  return color;
}
