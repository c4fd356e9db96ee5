// The packet traversal of bvh_packet.cpp, compiled once per instruction set there:
// included inside namespace avx2 under ENGINE_AVX2_BEGIN and again inside namespace
// avx512 under ENGINE_AVX512_BEGIN (the same operations, so the same bits; AVX-512VL
// gives the compiler 32 vector registers). No include guard, no includes.
namespace {

constexpr int kLanes = Bvh::kPacketSize;
constexpr float kInf = std::numeric_limits<float>::infinity();

// What the eight rays share and what each lane holds, made once per packet.
struct Packet {
  const Ray<float>* rays;
  __m256 o[3];            // per lane, by axis
  __m256 sx, sy, sz;      // the watertight test's shear, per lane
  int k[3];               // its permutation (kx, ky, kz), the same for every lane
  int nearRow[3], farRow[3];
  float oLo[3], oHi[3], invLo[3], invHi[3];
};

// False when the rays are not coherent enough to share a traversal.
bool makePacket(const Ray<float>* rays, Packet& p) {
  alignas(32) float o[3][kLanes], sx[kLanes], sy[kLanes], sz[kLanes];
  const TriangleRay<float> first(rays[0]);
  const BoundsRay<float> firstSlabs(rays[0]);
  p.k[0] = first.kx, p.k[1] = first.ky, p.k[2] = first.kz;
  for (int axis = 0; axis < 3; ++axis) {
    p.nearRow[axis] = axis + 3 * firstSlabs.dirIsNeg[axis];
    p.farRow[axis] = axis + 3 * (1 - firstSlabs.dirIsNeg[axis]);
    p.oLo[axis] = p.oHi[axis] = rays[0].o[axis];
    p.invLo[axis] = p.invHi[axis] = firstSlabs.invDir[axis];
  }
  for (int lane = 0; lane < kLanes; ++lane) {
    const TriangleRay<float> tri(rays[lane]);
    const BoundsRay<float> slabs(rays[lane]);
    if (tri.kx != p.k[0] || tri.ky != p.k[1] || tri.kz != p.k[2]) return false;
    for (int axis = 0; axis < 3; ++axis) {
      const float inv = slabs.invDir[axis];
      if (rays[lane].d[axis] == 0.0f || !std::isfinite(inv) || slabs.dirIsNeg[axis] != firstSlabs.dirIsNeg[axis]) return false;
      p.oLo[axis] = std::min(p.oLo[axis], rays[lane].o[axis]);
      p.oHi[axis] = std::max(p.oHi[axis], rays[lane].o[axis]);
      p.invLo[axis] = std::min(p.invLo[axis], inv);
      p.invHi[axis] = std::max(p.invHi[axis], inv);
      o[axis][lane] = rays[lane].o[axis];
    }
    sx[lane] = tri.sx;
    sy[lane] = tri.sy;
    sz[lane] = tri.sz;
  }
  p.rays = rays;
  for (int axis = 0; axis < 3; ++axis) p.o[axis] = _mm256_load_ps(o[axis]);
  p.sx = _mm256_load_ps(sx);
  p.sy = _mm256_load_ps(sy);
  p.sz = _mm256_load_ps(sz);
  return true;
}

// The eight children's boxes against the packet's interval: the mask of children some
// ray may enter before tMax (the largest of the lanes'), and where the first could.
int packetBoxes(const Bvh::Node& node, const Packet& p, float tMax, float tEntry[kLanes]) {
  static constexpr float kWiden = 1.0f + 2.0f * gamma<float>(3);
  __m256 t0 = _mm256_set1_ps(-kInf), t1 = _mm256_set1_ps(kInf);
  for (int axis = 0; axis < 3; ++axis) {
    const __m256 oLo = _mm256_set1_ps(p.oLo[axis]), oHi = _mm256_set1_ps(p.oHi[axis]);
    const __m256 invLo = _mm256_set1_ps(p.invLo[axis]), invHi = _mm256_set1_ps(p.invHi[axis]);
    const __m256 nearSlab = _mm256_load_ps(node.box[p.nearRow[axis]]);
    const __m256 farSlab = _mm256_load_ps(node.box[p.farRow[axis]]);
    const __m256 nLo = _mm256_sub_ps(nearSlab, oHi), nHi = _mm256_sub_ps(nearSlab, oLo);
    const __m256 fLo = _mm256_sub_ps(farSlab, oHi), fHi = _mm256_sub_ps(farSlab, oLo);
    const __m256 nearMin = _mm256_min_ps(_mm256_min_ps(_mm256_mul_ps(nLo, invLo), _mm256_mul_ps(nLo, invHi)),
                                         _mm256_min_ps(_mm256_mul_ps(nHi, invLo), _mm256_mul_ps(nHi, invHi)));
    const __m256 farMax = _mm256_max_ps(_mm256_max_ps(_mm256_mul_ps(fLo, invLo), _mm256_mul_ps(fLo, invHi)),
                                        _mm256_max_ps(_mm256_mul_ps(fHi, invLo), _mm256_mul_ps(fHi, invHi)));
    t0 = _mm256_max_ps(nearMin, t0);
    t1 = _mm256_min_ps(farMax, t1);
  }
  t1 = _mm256_mul_ps(t1, _mm256_set1_ps(kWiden));
  const __m256 inside =
      _mm256_and_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ), _mm256_cmp_ps(t1, _mm256_setzero_ps(), _CMP_GT_OQ));
  const __m256 hit = _mm256_and_ps(inside, _mm256_cmp_ps(t0, _mm256_set1_ps(tMax), _CMP_LT_OQ));
  _mm256_storeu_ps(tEntry, t0);
  return _mm256_movemask_ps(hit);
}

// Each lane's nearest hit so far.
struct PacketHits {
  __m256 t, b0, b1, b2;
  alignas(32) std::uint32_t triangle[kLanes];  // 4 * leaf + slot; kNoChild: none
  int mask = 0;

  float farthest() const {
    const __m128 half = _mm_max_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps(t, 1));
    const __m128 pair = _mm_max_ps(half, _mm_movehl_ps(half, half));
    return _mm_cvtss_f32(_mm_max_ss(pair, _mm_shuffle_ps(pair, pair, 1)));
  }
};

__m256 lt(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
__m256 gt(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
__m256 absolute(__m256 v) { return _mm256_and_ps(v, _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff))); }
__m256 max3(const __m256 v[3]) { return _mm256_max_ps(_mm256_max_ps(absolute(v[0]), absolute(v[1])), absolute(v[2])); }

// pbrt's bound on the error of t (intersectTriangle's deltaT), lane by lane.
__m256 errorOfT(__m256 e0, __m256 e1, __m256 e2, __m256 invDet, const __m256 x[3], const __m256 y[3],
                const __m256 z[3]) {
  const __m256 maxZt = max3(z), maxXt = max3(x), maxYt = max3(y);
  const __m256 g2 = _mm256_set1_ps(gamma<float>(2)), g3 = _mm256_set1_ps(gamma<float>(3)),
               g5 = _mm256_set1_ps(gamma<float>(5));
  const __m256 deltaZ = _mm256_mul_ps(g3, maxZt);
  const __m256 deltaX = _mm256_mul_ps(g5, _mm256_add_ps(maxXt, maxZt));
  const __m256 deltaY = _mm256_mul_ps(g5, _mm256_add_ps(maxYt, maxZt));
  const __m256 deltaE = _mm256_mul_ps(
      _mm256_set1_ps(2.0f),
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(g2, maxXt), maxYt), _mm256_mul_ps(deltaY, maxXt)),
                    _mm256_mul_ps(deltaX, maxYt)));
  const __m256 maxE = _mm256_max_ps(_mm256_max_ps(absolute(e0), absolute(e1)), absolute(e2));
  const __m256 sum =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(g3, maxE), maxZt), _mm256_mul_ps(deltaE, maxZt)),
                    _mm256_mul_ps(deltaZ, maxE));
  return _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(3.0f), sum), absolute(invDet));
}

// One triangle of a leaf (its slot) against the eight rays, operation for operation as
// intersectTriangle, each lane against its own nearest hit so far. A lane with an edge
// function of exactly zero goes to the scalar test, whose double fallback settles it.
void packetTriangle(const Bvh::Triangle4& leaf, int slot, std::uint32_t id, const Packet& p, PacketHits& hits) {
  __m256 x[3], y[3], z[3];
  for (int v = 0; v < 3; ++v) {
    x[v] = _mm256_sub_ps(_mm256_set1_ps(leaf.p[v][p.k[0]][slot]), p.o[p.k[0]]);
    y[v] = _mm256_sub_ps(_mm256_set1_ps(leaf.p[v][p.k[1]][slot]), p.o[p.k[1]]);
    z[v] = _mm256_sub_ps(_mm256_set1_ps(leaf.p[v][p.k[2]][slot]), p.o[p.k[2]]);
    x[v] = _mm256_add_ps(x[v], _mm256_mul_ps(p.sx, z[v]));
    y[v] = _mm256_add_ps(y[v], _mm256_mul_ps(p.sy, z[v]));
  }
  const __m256 e0 = _mm256_sub_ps(_mm256_mul_ps(x[1], y[2]), _mm256_mul_ps(y[1], x[2]));
  const __m256 e1 = _mm256_sub_ps(_mm256_mul_ps(x[2], y[0]), _mm256_mul_ps(y[2], x[0]));
  const __m256 e2 = _mm256_sub_ps(_mm256_mul_ps(x[0], y[1]), _mm256_mul_ps(y[0], x[1]));
  const __m256 zero = _mm256_setzero_ps();
  const __m256 anyZero = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(e0, zero, _CMP_EQ_OQ), _mm256_cmp_ps(e1, zero, _CMP_EQ_OQ)),
                                      _mm256_cmp_ps(e2, zero, _CMP_EQ_OQ));
  const __m256 anyNeg = _mm256_or_ps(_mm256_or_ps(lt(e0, zero), lt(e1, zero)), lt(e2, zero));
  const __m256 anyPos = _mm256_or_ps(_mm256_or_ps(gt(e0, zero), gt(e1, zero)), gt(e2, zero));
  __m256 ok = _mm256_andnot_ps(_mm256_or_ps(anyZero, _mm256_and_ps(anyNeg, anyPos)), _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
  const int zeroLanes = _mm256_movemask_ps(anyZero);
  if ((_mm256_movemask_ps(ok) | zeroLanes) == 0) return;
  if (_mm256_movemask_ps(ok) != 0) {
    const __m256 det = _mm256_add_ps(_mm256_add_ps(e0, e1), e2);
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(det, zero, _CMP_NEQ_UQ));
    for (int v = 0; v < 3; ++v) z[v] = _mm256_mul_ps(z[v], p.sz);
    const __m256 tScaled =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(e0, z[0]), _mm256_mul_ps(e1, z[1])), _mm256_mul_ps(e2, z[2]));
    const __m256 tMaxDet = _mm256_mul_ps(hits.t, det);
    const __m256 badNeg = _mm256_and_ps(lt(det, zero), _mm256_or_ps(_mm256_cmp_ps(tScaled, zero, _CMP_GE_OQ), lt(tScaled, tMaxDet)));
    const __m256 badPos = _mm256_and_ps(gt(det, zero), _mm256_or_ps(_mm256_cmp_ps(tScaled, zero, _CMP_LE_OQ), gt(tScaled, tMaxDet)));
    ok = _mm256_andnot_ps(_mm256_or_ps(badNeg, badPos), ok);
    if (_mm256_movemask_ps(ok) != 0) {
      const __m256 invDet = _mm256_div_ps(_mm256_set1_ps(1.0f), det);
      const __m256 t = _mm256_mul_ps(tScaled, invDet);
      // Strictly before the lane's nearest so far, as (0, tMax) says: the scaled test
      // above rounds, and may let through a t equal to it.
      const __m256 hit = _mm256_and_ps(_mm256_and_ps(ok, lt(t, hits.t)), gt(t, errorOfT(e0, e1, e2, invDet, x, y, z)));
      hits.t = _mm256_blendv_ps(hits.t, t, hit);
      hits.b0 = _mm256_blendv_ps(hits.b0, _mm256_mul_ps(e0, invDet), hit);
      hits.b1 = _mm256_blendv_ps(hits.b1, _mm256_mul_ps(e1, invDet), hit);
      hits.b2 = _mm256_blendv_ps(hits.b2, _mm256_mul_ps(e2, invDet), hit);
      for (int mask = _mm256_movemask_ps(hit); mask != 0; mask &= mask - 1) hits.triangle[__builtin_ctz(unsigned(mask))] = id;
      hits.mask |= _mm256_movemask_ps(hit);
    }
  }
  if (zeroLanes == 0) return;
  alignas(32) float t[kLanes], b0[kLanes], b1[kLanes], b2[kLanes];
  _mm256_store_ps(t, hits.t);
  _mm256_store_ps(b0, hits.b0);
  _mm256_store_ps(b1, hits.b1);
  _mm256_store_ps(b2, hits.b2);
  for (int mask = zeroLanes; mask != 0; mask &= mask - 1) {
    const int lane = __builtin_ctz(unsigned(mask));
    if (auto hit = intersectTriangle(TriangleRay<float>(p.rays[lane]), t[lane], leaf.vertex(0, slot), leaf.vertex(1, slot),
                                     leaf.vertex(2, slot));
        hit && hit->t < t[lane]) {
      t[lane] = hit->t;
      b0[lane] = hit->b0;
      b1[lane] = hit->b1;
      b2[lane] = hit->b2;
      hits.triangle[lane] = id;
      hits.mask |= 1 << lane;
    }
  }
  hits.t = _mm256_load_ps(t);
  hits.b0 = _mm256_load_ps(b0);
  hits.b1 = _mm256_load_ps(b1);
  hits.b2 = _mm256_load_ps(b2);
}

// The traversal of bvh_traverse.inl for the packet: nearest child first, a popped
// entry skipped when every lane's nearest hit is closer than the packet's entry.
void tracePacket(const Bvh::View& bvh, const Packet& p, PacketHits& hits) {
  struct Entry {
    std::uint32_t ref;
    float tEntry;
  };
  Entry stack[Bvh::kStackSize];
  int top = 0;
  float tMax = hits.farthest();
  std::uint32_t ref = bvh.root;
  for (;;) {
    while (!Bvh::isLeaf(ref)) {
      const Bvh::Node& node = bvh.nodes[ref];
      float tEntry[kLanes];
      unsigned mask = unsigned(packetBoxes(node, p, tMax, tEntry));
      if (mask == 0) goto pop;
      const int base = top;
      for (; mask != 0; mask &= mask - 1) {
        const int k = __builtin_ctz(mask);
        const Entry e{node.child[k], tEntry[k]};
        int at = top++;
        for (; at > base && stack[at - 1].tEntry <= e.tEntry; --at) stack[at] = stack[at - 1];
        stack[at] = e;
      }
      ref = stack[--top].ref;
    }
    {
      const std::uint32_t leaf = Bvh::leafIndex(ref);
      const int count = int(Bvh::leafCount(ref));
      for (int slot = 0; slot < count; ++slot) packetTriangle(bvh.leaves[leaf], slot, 4 * leaf + std::uint32_t(slot), p, hits);
      tMax = hits.farthest();
    }
  pop:
    do {
      if (top == 0) return;
      --top;
    } while (!(stack[top].tEntry < tMax));
    ref = stack[top].ref;
  }
}

bool tracePacketAvx2(const Bvh::View& bvh, const Ray<float>* rays, BvhHit<float>* out, std::uint32_t& hitMask) {
  Packet p;
  if (!makePacket(rays, p)) return false;
  alignas(32) float t[kLanes];
  for (int lane = 0; lane < kLanes; ++lane) t[lane] = rays[lane].tMax;
  PacketHits hits;
  hits.t = _mm256_load_ps(t);
  hits.b0 = hits.b1 = hits.b2 = _mm256_setzero_ps();
  std::fill(std::begin(hits.triangle), std::end(hits.triangle), Bvh::kNoChild);
  tracePacket(bvh, p, hits);
  alignas(32) float b0[kLanes], b1[kLanes], b2[kLanes];
  _mm256_store_ps(t, hits.t);
  _mm256_store_ps(b0, hits.b0);
  _mm256_store_ps(b1, hits.b1);
  _mm256_store_ps(b2, hits.b2);
  for (int mask = hits.mask; mask != 0; mask &= mask - 1) {
    const int lane = __builtin_ctz(unsigned(mask));
    out[lane] = BvhHit<float>{TriangleIntersection<float>{b0[lane], b1[lane], b2[lane], t[lane]},
                              bvh.order[hits.triangle[lane]]};
  }
  hitMask = std::uint32_t(hits.mask);
  return true;
}

}  // namespace
