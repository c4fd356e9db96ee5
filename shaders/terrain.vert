#version 450 core
// CDLOD terrain: one kPatchQuads^2 grid instanced per selected patch. Mirrors
// engine/terrain/lod.cpp patchVertex (and patchNormal for v_normal) operation for
// operation: change both together.
// Positions are camera-relative and built from integer sample indices minus the
// camera's integer cell, so nothing large is ever held in a float and a vertex
// shared by two patches gets the same bits in both.
//
// Variants: DEPTH_ONLY (the sun's shadow pass: position only, drawn with the
// light's matrix).
#define PATCH_QUADS 32
#define NODE_QUADS 64
#define MAX_LEVELS 16
// Height pages live in an atlas: PAGE_ATLAS x PAGE_ATLAS pages of PAGE_SIDE^2
// texels per array layer (engine/terrain/terrain_renderer.h, kPageAtlas).
#define PAGE_SIDE 67
#define PAGE_ATLAS 4

#include "common/frame.glsl"

layout(location = 0) in ivec2 a_grid;      // (i, j) in [0, PATCH_QUADS]
layout(location = 1) in ivec4 a_patch;     // global sample of vertex (0,0), level, page slot

layout(binding = UNIT_TERRAIN_HEIGHTS) uniform sampler2DArray u_heightPages;

#ifdef DEPTH_ONLY
uniform mat4 u_lightViewProjection;  // camera-relative world -> the light's clip space
#endif
uniform ivec2 u_cameraCell;
uniform vec2 u_cameraFraction;
uniform ivec2 u_cells;
uniform float u_cameraHeight;
uniform float u_morphDy2;
uniform float u_spacing;
uniform float u_morphStart[MAX_LEVELS];
uniform float u_morphEnd[MAX_LEVELS];
uniform vec2 u_uvOffset;
uniform float u_tileMetres;

#ifndef DEPTH_ONLY
out vec3 v_position;  // camera-relative world position
out vec3 v_normal;
out float v_height;   // metres above the terrain origin
out vec2 v_uv;
#endif

// Texel of the page's sample (0,0) border corner in the atlas, and the layer.
ivec3 pageCorner(int slot) {
  int tile = slot % (PAGE_ATLAS * PAGE_ATLAS);
  return ivec3(ivec2(tile % PAGE_ATLAS, tile / PAGE_ATLAS) * PAGE_SIDE, slot / (PAGE_ATLAS * PAGE_ATLAS));
}

float pageHeight(ivec2 local, ivec3 corner) {
  // The page has a one-sample border: node sample (0,0) is texel (1,1).
  return texelFetch(u_heightPages, ivec3(corner.xy + local + 1, corner.z), 0).r;
}

vec3 pageNormal(ivec2 local, ivec3 corner, float step) {
  float l = pageHeight(local - ivec2(1, 0), corner), r = pageHeight(local + ivec2(1, 0), corner);
  float d = pageHeight(local - ivec2(0, 1), corner), u = pageHeight(local + ivec2(0, 1), corner);
  return normalize(vec3(l - r, 2.0 * step, d - u));
}

void main() {
  int level = a_patch.z;
  ivec3 corner = pageCorner(a_patch.w);
  int s = 1 << level;
  ivec2 g = a_patch.xy + a_grid * s;
  ivec2 p = min(g, u_cells);
  vec2 rel = vec2(p - u_cameraCell) - u_cameraFraction;
  float x = rel.x * u_spacing;
  float z = rel.y * u_spacing;
  float d = sqrt(x * x + z * z + u_morphDy2);
  float start = u_morphStart[level];
  float end = u_morphEnd[level];
  float k = clamp((d - start) / (end - start), 0.0, 1.0);

  // Odd vertices slide onto their even neighbour: at k = 1 the grid is the parent's.
  ivec2 odd = a_grid & 1;
  ivec2 q = min(g - odd * s, u_cells);
  vec2 relQ = vec2(q - u_cameraCell) - u_cameraFraction;
  ivec2 local = (a_patch.xy / s) % NODE_QUADS + a_grid;
  float hp = pageHeight(local, corner);
  float hq = pageHeight(local - odd, corner);
  float w = 1.0 - k;
  vec2 xz = (rel * w + relQ * k) * u_spacing;
  float h = hp * w + hq * k;
  vec3 position = vec3(xz.x, h - u_cameraHeight, xz.y);

#ifdef DEPTH_ONLY
  gl_Position = u_lightViewProjection * vec4(position, 1.0);
#else
  float step = float(s) * u_spacing;
  v_normal = normalize(pageNormal(local, corner, step) * w + pageNormal(local - odd, corner, step) * k);
  v_position = position;
  v_height = h;
  v_uv = xz / u_tileMetres + u_uvOffset;
  gl_Position = u_viewProjection * vec4(position, 1.0);
#endif
}
