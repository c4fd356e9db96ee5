#version 450 core
// CDLOD terrain: one kPatchQuads^2 grid instanced per selected patch. Mirrors
// engine/terrain/lod.cpp patchVertex operation for operation: change both together.
// Positions are camera-relative and built from integer sample indices minus the
// camera's integer cell, so nothing large is ever held in a float and a vertex
// shared by two patches gets the same bits in both.
#define PATCH_QUADS 32
#define NODE_QUADS 64
#define MAX_LEVELS 16

layout(location = 0) in ivec2 a_grid;      // (i, j) in [0, PATCH_QUADS]
layout(location = 1) in ivec4 a_patch;     // global sample of vertex (0,0), level, page slot

layout(binding = 0) uniform sampler2DArray u_heightPages;

uniform mat4 u_viewProjection;
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

out vec3 v_position;  // camera-relative world position
out vec3 v_normal;
out float v_height;   // metres above the terrain origin
out vec2 v_uv;

float pageHeight(ivec2 local, int slot) {
  // The page has a one-sample border: node sample (0,0) is texel (1,1).
  return texelFetch(u_heightPages, ivec3(local + 1, slot), 0).r;
}

vec3 pageNormal(ivec2 local, int slot, float step) {
  float l = pageHeight(local - ivec2(1, 0), slot), r = pageHeight(local + ivec2(1, 0), slot);
  float d = pageHeight(local - ivec2(0, 1), slot), u = pageHeight(local + ivec2(0, 1), slot);
  return normalize(vec3(l - r, 2.0 * step, d - u));
}

void main() {
  int level = a_patch.z;
  int slot = a_patch.w;
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
  float hp = pageHeight(local, slot);
  float hq = pageHeight(local - odd, slot);
  float w = 1.0 - k;
  vec2 xz = (rel * w + relQ * k) * u_spacing;
  float h = hp * w + hq * k;
  vec3 position = vec3(xz.x, h - u_cameraHeight, xz.y);

  float step = float(s) * u_spacing;
  v_normal = normalize(pageNormal(local, slot, step) * w + pageNormal(local - odd, slot, step) * k);
  v_position = position;
  v_height = h;
  v_uv = xz / u_tileMetres + u_uvOffset;
  gl_Position = u_viewProjection * vec4(position, 1.0);
}
