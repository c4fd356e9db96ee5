#version 450 core
// Terrain materials: grass, rock and snow blended by height and slope, shaded into
// the HDR target with the same frame block, lighting model (common/shading.glsl),
// sun and point shadows and fog as scene.frag, so a rock and the ground beside it
// agree. Variants as scene.frag: CLASSIC, AMBIENT_SH, AMBIENT_IBL, SUN_SHADOWS,
// POINT_SHADOWS, FOG.
#include "common/frame.glsl"
#include "common/shading.glsl"
#include "common/shadows.glsl"
#include "common/direct_light.glsl"
#include "common/fog.glsl"
#include "common/output.glsl"

in vec3 v_position;
in vec3 v_normal;
in float v_height;
in vec2 v_uv;

layout(binding = UNIT_TERRAIN_LAYERS) uniform sampler2D u_grassTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 1) uniform sampler2D u_rockTexture;
layout(binding = UNIT_TERRAIN_LAYERS + 2) uniform sampler2D u_snowTexture;
uniform float u_heightScale;

layout(location = 0) out vec4 o_color;

// Layer weights, summing to one: rock where steep, snow high up where it can lie
// (not on cliffs), grass elsewhere. The texture's own brightness jitters the snow
// line so it does not follow a contour exactly. The ray tracer's twin is
// engine::terrain::layerWeights (engine/terrain/materials.cpp), which also holds
// main's scales, roughness and highlight below (materials.h): change both together.
vec3 layerWeights(float height01, float slope, float jitter) {
  float rock = smoothstep(0.28, 0.5, slope);
  float snow = smoothstep(0.6, 0.7, height01 + 0.05 * jitter) * (1.0 - smoothstep(0.35, 0.6, slope));
  float grass = max(1.0 - rock - snow, 0.0);
  return vec3(grass, rock, snow) / max(grass + rock + snow, 1e-4);
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 toEye = normalize(-v_position);  // the camera sits at the origin
  // Two scales of the same layer break up visible repetition.
  vec2 uvFar = v_uv * 0.173;
  vec3 grass = texture(u_grassTexture, v_uv).rgb * texture(u_grassTexture, uvFar).rgb * 2.0;
  vec3 rock = texture(u_rockTexture, v_uv).rgb * texture(u_rockTexture, uvFar).rgb * 2.0;
  vec3 snow = texture(u_snowTexture, v_uv).rgb;
  vec3 w = layerWeights(v_height / u_heightScale, 1.0 - n.y, rock.r * 2.0 - 0.5);
  vec3 albedo = grass * w.x + rock * w.y + snow * w.z;
  // Rough dielectrics; snow a little glossier. Classic weights: the scene's ambient
  // (frame block), full diffuse, a faint highlight on snow.
  float roughness = dot(w, vec3(0.95, 0.8, 0.5));
  float specular = mix(0.02, 0.25, w.z);
  Surface s = Surface(albedo, n, toEye, v_position, 0.0, roughness, u_ambientSky.w, 1.0, specular, 24.0, 0.0);
  vec3 color = shadeAmbient(s) + shadeDirectLight(s, n);
#ifdef FOG
  color = applyFog(color, length(v_position), u_fog.rgb, u_fog.w);
#endif
  o_color = targetColor(color, 1.0);
}
