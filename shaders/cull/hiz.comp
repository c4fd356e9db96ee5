#version 450 core
// One level of the hierarchical-Z pyramid (render/gpu_cull.h, render/cull_math.h's
// HiZ::build is its CPU twin): each level keeps the least depth (reverse-Z: the
// farthest) of the texels below it, level 1 of the view's depth itself, its last
// column and row taking everything up to the edge of an odd-sized level, so that
// no pixel of the view is left out of any level.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = UNIT_HIZ_SOURCE) uniform sampler2D u_source;  // the depth, or the pyramid itself
layout(binding = IMAGE_HIZ_LEVEL, r32f) writeonly uniform image2D u_level;

uniform int u_sourceLevel;    // the level of u_source read
uniform ivec2 u_sourceSize;   // its size
uniform ivec2 u_size;         // the size of the level written

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, u_size))) return;
  const ivec2 last = ivec2(p.x == u_size.x - 1 ? u_sourceSize.x - 1 : 2 * p.x + 1,
                           p.y == u_size.y - 1 ? u_sourceSize.y - 1 : 2 * p.y + 1);
  float farthest = texelFetch(u_source, min(2 * p, u_sourceSize - 1), u_sourceLevel).r;
  for (int y = 2 * p.y; y <= last.y; ++y)
    for (int x = 2 * p.x; x <= last.x; ++x) farthest = min(farthest, texelFetch(u_source, ivec2(x, y), u_sourceLevel).r);
  imageStore(u_level, p, vec4(farthest));
}
