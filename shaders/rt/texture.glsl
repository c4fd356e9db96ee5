// The CPU tracer's textures on the GPU (raytrace/texture.cpp's RtTexture, flattened
// by gputrace/gpu_textures.h): every mipmap level in linear RGBA in one texel array,
// sampled as RtTexture::sampleRgba does, operation for operation: the uv set, the
// KHR_texture_transform matrix, GL's wrap of coordinates and texel indices,
// bilinear between texel centres, and the level of detail a ray cone's footprint
// picks, blended trilinearly. Change both together.

#define RT_TEXTURE_LEVELS 16  // gputrace/gpu_textures.h's kGpuTextureLevels

struct RtTexture {
  ivec4 info;          // levels, wrap s, wrap t (GL's enums), uv set
  vec4 transform[3];   // the uv transform's columns; [0].w footprint scale, [1].w 1 when not the identity
  ivec4 level[RT_TEXTURE_LEVELS];  // first texel, width, height
};

// Declared only where the scene has textures (RT_TEXTURES): a compute shader has at
// most 16 storage blocks, and GLSL counts every std430 block declared.
#ifdef RT_TEXTURES
layout(std430, binding = BUFFER_RT_TEXTURES) readonly buffer RtTextures { RtTexture rtTextures[]; };
layout(std430, binding = BUFFER_RT_TEXELS) readonly buffer RtTexels { vec4 rtTexels[]; };
#endif

const int RT_WRAP_REPEAT = 10497;
const int RT_WRAP_CLAMP = 33071;
const int RT_WRAP_MIRRORED = 33648;

// wrapIndex: GL's wrap of texel index i of n.
int rtWrapIndex(int i, int n, int mode) {
  if (mode == RT_WRAP_CLAMP) return clamp(i, 0, n - 1);
  if (mode == RT_WRAP_MIRRORED) {
    int a = wrapMod(i, 2 * n) - n;
    return (n - 1) - (a >= 0 ? a : -(1 + a));
  }
  return wrapMod(i, n);
}

// reduce: a coordinate brought to one period of its wrap (two for mirrored repeat).
float rtReduce(float x, int mode) {
  if (mode == RT_WRAP_CLAMP) return clamp(x, 0.0, 1.0);
  if (mode == RT_WRAP_MIRRORED) {
    precise float r = x - 2.0 * floor(0.5 * x);
    return r;
  }
  precise float r = x - floor(x);
  return r;
}

#ifdef RT_TEXTURES
vec4 rtBilinear(int index, int level, vec2 uv) {
  ivec4 l = rtTextures[index].level[level];
  ivec4 info = rtTextures[index].info;
  int w = l.y, h = l.z;
  precise float u = rtReduce(uv.x, info.y) * float(w) - 0.5;
  precise float v = rtReduce(uv.y, info.z) * float(h) - 0.5;
  if (isinf(u) || isnan(u) || isinf(v) || isnan(v)) return rtTexels[l.x];
  float fu = floor(u), fv = floor(v);
  precise float tu = u - fu, tv = v - fv;
  int x0 = rtWrapIndex(int(fu), w, info.y), x1 = rtWrapIndex(int(fu) + 1, w, info.y);
  int y0 = rtWrapIndex(int(fv), h, info.z), y1 = rtWrapIndex(int(fv) + 1, h, info.z);
  vec4 a = rtTexels[l.x + y0 * w + x0], b = rtTexels[l.x + y0 * w + x1];
  vec4 c = rtTexels[l.x + y1 * w + x0], d = rtTexels[l.x + y1 * w + x1];
  return mixAsGlm(mixAsGlm(a, b, tu), mixAsGlm(c, d, tu), tv);
}

// RtTexture::sampleRgba at the hit's uv sets with the footprint in TEXCOORD_0's units.
// The two levels of a trilinear read go through one bilinear call site (llvmpipe
// inlines every call: each site is another copy of the code to compile).
vec4 rtSampleTexture(int index, vec2 uv0, vec2 uv1, float footprint) {
  ivec4 info = rtTextures[index].info;
  vec2 uv = info.w == 1 ? uv1 : uv0;
  vec4 t1 = rtTextures[index].transform[1];
  if (t1.w != 0.0) {
    vec4 t0 = rtTextures[index].transform[0], t2 = rtTextures[index].transform[2];
    precise vec2 t = vec2(t0.x * uv.x + t1.x * uv.y + t2.x, t0.y * uv.x + t1.y * uv.y + t2.y);
    uv = t;
    footprint *= t0.w;
  }
  ivec4 base = rtTextures[index].level[0];
  precise float texels = footprint * float(max(base.y, base.z));
  float lod = texels > 1.0 ? min(log2(texels), float(info.x - 1)) : 0.0;
  int below = lod > 0.0 ? int(lod) : 0;
  precise float t = lod > 0.0 ? lod - float(below) : 0.0;
  vec4 level[2];
  for (int k = 0; k < (t > 0.0 ? 2 : 1); ++k) level[k] = rtBilinear(index, below + k, uv);
  return t > 0.0 ? mixAsGlm(level[0], level[1], t) : level[0];
}
#endif
