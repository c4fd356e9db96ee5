// PCG32 (raytrace/rng.h) on the GPU, its 64-bit words made of two uints (lo, hi): the
// same generator, the same per-pixel and per-sample streams as the CPU's, so that a
// kernel draws the very numbers its CPU twin draws.

uvec2 u64Add(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}
uvec2 u64Mul(uvec2 a, uvec2 b) {
  uint hi, lo;
  umulExtended(a.x, b.x, hi, lo);
  return uvec2(lo, hi + a.x * b.y + a.y * b.x);
}
uvec2 u64Shr(uvec2 a, int n) {  // 0 < n < 64
  if (n >= 32) return uvec2(a.y >> (n - 32), 0u);
  return uvec2((a.x >> n) | (a.y << (32 - n)), a.y >> n);
}
uvec2 u64Shl1(uvec2 a) { return uvec2(a.x << 1, (a.y << 1) | (a.x >> 31)); }

uvec2 mixBits(uvec2 v) {
  v ^= u64Shr(v, 31);
  v = u64Mul(v, uvec2(0x728ea185u, 0x7fb5d329u));
  v ^= u64Shr(v, 27);
  v = u64Mul(v, uvec2(0xbc2dd44du, 0x81dadef4u));
  v ^= u64Shr(v, 33);
  return v;
}

struct Pcg32 {
  uvec2 state, inc;
};

uint pcgNext(inout Pcg32 g) {
  uvec2 old = g.state;
  g.state = u64Add(u64Mul(old, uvec2(0x4c957f2du, 0x5851f42du)), g.inc);
  uint xorShifted = u64Shr(u64Shr(old, 18) ^ old, 27).x;
  uint rot = old.y >> 27;
  return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31u));
}

float pcgUniform(inout Pcg32 g) { return float(pcgNext(g) >> 8) * 5.9604644775390625e-8; }

// Pcg32::uniform2: y drawn first, then x.
vec2 pcgUniform2(inout Pcg32 g) {
  float y = pcgUniform(g);
  float x = pcgUniform(g);
  return vec2(x, y);
}

// Pcg32(seed, stream): setSequence.
Pcg32 pcgSeeded(uvec2 seed, uvec2 stream) {
  Pcg32 g;
  g.state = uvec2(0u);
  g.inc = u64Shl1(stream) | uvec2(1u, 0u);
  pcgNext(g);
  g.state = u64Add(g.state, seed);
  pcgNext(g);
  return g;
}

// Pcg32::forPixel: key = x << 32 | y.
Pcg32 pcgForPixel(uvec2 seed, int x, int y) {
  uvec2 key = uvec2(uint(y), uint(x));
  return pcgSeeded(mixBits(seed ^ mixBits(key)), mixBits(u64Add(key, uvec2(0x7f4a7c15u, 0x9e3779b9u))));
}

// Pcg32::forSample: a stream of its own for each sample of the pixel.
Pcg32 pcgForSample(uvec2 seed, int x, int y, int s) {
  uvec2 key = uvec2(uint(y), uint(x));
  uvec2 salt = mixBits(u64Add(uvec2(uint(s), 0u), uvec2(0xd9b4e019u, 0x632be59bu)));
  return pcgSeeded(mixBits(seed ^ mixBits(key) ^ salt), mixBits(u64Add(key, uvec2(0x7f4a7c15u, 0x9e3779b9u))));
}
