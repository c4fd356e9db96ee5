#version 450 core
// The terrain shaded once a pixel (common/terrain_material.glsl), from the surface
// terrain.frag's TERRAIN_SURFACE variant left where the terrain is nearest: a
// full-screen triangle (sky.vert) drawn where the stencil marks terrain. Variants as
// terrain.frag's.
in vec3 v_direction;  // camera-relative world, through the pixel's centre

layout(binding = UNIT_TERRAIN_SURFACE) uniform sampler2D u_surface;
uniform float u_cameraHeight;  // the camera above the terrain's origin
uniform vec2 u_uvOffset;       // terrain.vert's
uniform float u_tileMetres;

#define TERRAIN_LAYER(t, uv, lod) textureLod(t, uv, lod)
#include "common/terrain_material.glsl"

layout(location = 0) out vec4 o_color;

void main() {
  vec4 surface = texelFetch(u_surface, ivec2(gl_FragCoord.xy), 0);
  vec3 position = normalize(v_direction) * surface.x;
  vec3 n = vec3(surface.y, sqrt(max(1.0 - dot(surface.yz, surface.yz), 0.0)), surface.z);
  vec2 lod = vec2(surface.w, surface.w + log2(TERRAIN_FAR_LAYER_SCALE));
  vec2 uv = position.xz / u_tileMetres + u_uvOffset;
  o_color = targetColor(terrainColor(position, n, position.y + u_cameraHeight, uv, lod), 1.0);
}
