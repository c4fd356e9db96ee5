#version 450 core
// The terrain where its patches are drawn (common/terrain_material.glsl). Variants
// as scene.frag: CLASSIC, AMBIENT_SH, AMBIENT_IBL, SUN_SHADOWS, POINT_SHADOWS, FOG;
// and TERRAIN_SURFACE: no shading, only what terrain_deferred.frag needs to shade the
// pixel later, once (the patches' far triangles cover a pixel or two each, and
// llvmpipe shades eight lanes at a time).
in vec3 v_position;
in vec3 v_normal;
in float v_height;
in vec2 v_uv;

#ifdef TERRAIN_SURFACE
layout(binding = UNIT_TERRAIN_LAYERS) uniform sampler2D u_grassTexture;
// x: distance from the camera; yz: the normal's x and z (its y is positive on a
// height field); w: the near layer scale's texture level of detail, which the
// deferred pass cannot take from its neighbours (they may be other surfaces).
layout(location = 0) out vec4 o_surface;

void main() {
  vec3 n = normalize(v_normal);
  o_surface = vec4(length(v_position), n.x, n.z, textureQueryLod(u_grassTexture, v_uv).y);
}
#else
#define TERRAIN_LAYER(t, uv, lod) texture(t, uv)
#include "common/terrain_material.glsl"

layout(location = 0) out vec4 o_color;

void main() {
  o_color = targetColor(terrainColor(v_position, normalize(v_normal), v_height, v_uv, vec2(0.0)), 1.0);
}
#endif
