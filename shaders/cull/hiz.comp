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
  float farthest;
  if (last == 2 * p + 1 && u_sourceLevel == 0) {
    // The usual 2 x 2 of a base level (GLSL has no gather at a chosen level): one
    // gather at their shared corner, exactly between texel centres. llvmpipe does
    // it as one texture operation; level 1 at 1280 x 720, four fetches a texel,
    // took 6-7 ms, gathered 2.5.
    const vec4 four = textureGather(u_source, vec2(2 * p + 1) / vec2(u_sourceSize));
    farthest = min(min(four.x, four.y), min(four.z, four.w));
  } else {
    farthest = texelFetch(u_source, min(2 * p, u_sourceSize - 1), u_sourceLevel).r;
    for (int y = 2 * p.y; y <= last.y; ++y)
      for (int x = 2 * p.x; x <= last.x; ++x) farthest = min(farthest, texelFetch(u_source, ivec2(x, y), u_sourceLevel).r);
  }
  imageStore(u_level, p, vec4(farthest));
}
