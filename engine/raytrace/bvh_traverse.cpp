// The BVH's traversal: the box and leaf tests, the traversal compiled once per
// instruction set (bvh_traverse.inl) and the choice between them at run time. Kept
// apart from the builder (bvh.cpp) because this file is compiled without
// auto-vectorisation (see CMakeLists.txt), which the builder's bounds arithmetic
// gains from.
#include <immintrin.h>

#include <atomic>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "raytrace/avx2_region.h"
#include "raytrace/bvh.h"

namespace engine::rt {
namespace {

template <typename T>
Vec3<T> toT(const glm::vec3& v) {
  return Vec3<T>(v);
}

// The per-ray part of the box test: the ray's origin, inverse direction and slab
// order. Any precision: intersectBounds on each child box in turn.
template <typename T>
class ChildBoxTest {
 public:
  explicit ChildBoxTest(const Ray<T>& ray) : ray_(ray), slabs_(ray) {}

  // The mask of the children hit before tMax, and their entry distances.
  int operator()(const Bvh::Node& node, T tMax, T tEntry[Bvh::kWidth]) const {
    int mask = 0;
    for (int i = 0; i < Bvh::kWidth; ++i) {
      Bounds3f b;
      b.min = glm::vec3(node.box[0][i], node.box[1][i], node.box[2][i]);
      b.max = glm::vec3(node.box[3][i], node.box[4][i], node.box[5][i]);
      if (intersectBounds(b, ray_, tMax, slabs_.invDir, slabs_.dirIsNeg, tEntry[i])) mask |= 1 << i;
    }
    return mask;
  }

 protected:
  Ray<T> ray_;
  BoundsRay<T> slabs_;
};

// What the SIMD box tests share: the near and far rows of each axis, chosen once per
// ray. They give intersectBounds' answers bit for bit: max and min return their
// second operand when either is NaN, which drops an axis whose slab the ray lies in
// exactly as the scalar test's comparisons do (the NaN becomes the unbounded start
// value), and widening the far distance once after the minimum equals widening each
// axis' before it, since rounding is monotonic.
//
// The rows are kept as offsets in floats from the node's first, pointer-sized: as
// int row numbers each of the six loads a node took a sign extension and a shift.
class SimdBoxRows : public ChildBoxTest<float> {
 public:
  explicit SimdBoxRows(const Ray<float>& ray) : ChildBoxTest<float>(ray) {
    for (int axis = 0; axis < 3; ++axis) {
      near_[axis] = std::ptrdiff_t(axis + 3 * slabs_.dirIsNeg[axis]) * Bvh::kWidth;
      far_[axis] = std::ptrdiff_t(axis + 3 * (1 - slabs_.dirIsNeg[axis])) * Bvh::kWidth;
    }
  }

 protected:
  static constexpr float kWiden = 1.0f + 2.0f * gamma<float>(3);
  static const float* rows(const Bvh::Node& node) { return &node.box[0][0]; }
  std::ptrdiff_t near_[3], far_[3];
};

// Float rays with SSE (part of every x86-64): the eight boxes as two halves of four.
class ChildBoxTestSse : public SimdBoxRows {
 public:
  explicit ChildBoxTestSse(const Ray<float>& ray) : SimdBoxRows(ray) {
    for (int axis = 0; axis < 3; ++axis) {
      o_[axis] = _mm_set1_ps(ray.o[axis]);
      inv_[axis] = _mm_set1_ps(slabs_.invDir[axis]);
    }
  }

  [[gnu::always_inline]] int operator()(const Bvh::Node& node, float tMax, float tEntry[Bvh::kWidth]) const {
    int mask = 0;
    for (int half = 0; half < Bvh::kWidth; half += 4) {
      __m128 t0 = _mm_set1_ps(-std::numeric_limits<float>::infinity());
      __m128 t1 = _mm_set1_ps(std::numeric_limits<float>::infinity());
      for (int axis = 0; axis < 3; ++axis) {
        const __m128 nearSlab = _mm_load_ps(rows(node) + near_[axis] + half);
        const __m128 farSlab = _mm_load_ps(rows(node) + far_[axis] + half);
        t0 = _mm_max_ps(_mm_mul_ps(_mm_sub_ps(nearSlab, o_[axis]), inv_[axis]), t0);
        t1 = _mm_min_ps(_mm_mul_ps(_mm_sub_ps(farSlab, o_[axis]), inv_[axis]), t1);
      }
      t1 = _mm_mul_ps(t1, _mm_set1_ps(kWiden));
      const __m128 inside = _mm_and_ps(_mm_cmple_ps(t0, t1), _mm_cmpgt_ps(t1, _mm_setzero_ps()));
      const __m128 hit = _mm_and_ps(inside, _mm_cmplt_ps(t0, _mm_set1_ps(tMax)));
      _mm_storeu_ps(tEntry + half, t0);
      mask |= _mm_movemask_ps(hit) << half;
    }
    return mask;
  }

 private:
  __m128 o_[3], inv_[3];
};

// A leaf's triangles against one ray, in any precision: the watertight test on each in
// turn. Returns the lane of the nearest hit before tMax (or, kAnyHit, the first),
// shrinking tMax to it; -1 when none.
template <typename T>
class LeafTest {
 public:
  explicit LeafTest(const Ray<T>& ray) : ray_(ray) {}

  template <bool kAnyHit>
  int intersect(const Bvh::Triangle4& leaf, std::uint32_t count, T& tMax, TriangleIntersection<T>& out) const {
    int found = -1;
    for (int lane = 0; lane < int(count); ++lane) {
      if (auto hit = intersectTriangle(ray_, tMax, toT<T>(leaf.vertex(0, lane)), toT<T>(leaf.vertex(1, lane)),
                                       toT<T>(leaf.vertex(2, lane)))) {
        out = *hit;
        tMax = hit->t;
        found = lane;
        if constexpr (kAnyHit) break;
      }
    }
    return found;
  }

 private:
  TriangleRay<T> ray_;
};

// Float rays: the same test on all four lanes at once, operation for operation as
// intersectTriangle writes it (no fused multiply-add), so each lane's t and
// barycentrics are bit for bit the scalar ones. A lane with an edge function of
// exactly zero is left to the scalar test, whose double fallback settles it. Of
// several hits the nearest wins, the lower lane on a tie.
template <>
class LeafTest<float> {
 public:
  // The permutation and shear from a TriangleRay made here and dropped: kept as a
  // member, its small int fields were read back as one word, a store-forwarding
  // stall on every ray. The rare scalar fallback makes its own.
  explicit LeafTest(const Ray<float>& ray) : ray_(ray) {
    const TriangleRay<float> r(ray);
    const int k[3] = {r.kx, r.ky, r.kz};
    for (int axis = 0; axis < 3; ++axis) {
      row_[axis] = k[axis];  // pointer-sized, as SimdBoxRows' offsets
      o_[axis] = _mm_set1_ps(ray.o[k[axis]]);
    }
    sx_ = _mm_set1_ps(r.sx);
    sy_ = _mm_set1_ps(r.sy);
    sz_ = _mm_set1_ps(r.sz);
  }

  template <bool kAnyHit>
  [[gnu::always_inline]] int intersect(const Bvh::Triangle4& leaf, std::uint32_t count, float& tMax,
                                       TriangleIntersection<float>& out) const {
    const __m128 valid = _mm_castsi128_ps(_mm_cmplt_epi32(_mm_set_epi32(3, 2, 1, 0), _mm_set1_epi32(int(count))));
    __m128 x[3], y[3], z[3];
    for (int v = 0; v < 3; ++v) {
      x[v] = _mm_sub_ps(_mm_load_ps(leaf.p[v][row_[0]]), o_[0]);
      y[v] = _mm_sub_ps(_mm_load_ps(leaf.p[v][row_[1]]), o_[1]);
      z[v] = _mm_sub_ps(_mm_load_ps(leaf.p[v][row_[2]]), o_[2]);
      x[v] = _mm_add_ps(x[v], _mm_mul_ps(sx_, z[v]));
      y[v] = _mm_add_ps(y[v], _mm_mul_ps(sy_, z[v]));
    }
    const __m128 e0 = _mm_sub_ps(_mm_mul_ps(x[1], y[2]), _mm_mul_ps(y[1], x[2]));
    const __m128 e1 = _mm_sub_ps(_mm_mul_ps(x[2], y[0]), _mm_mul_ps(y[2], x[0]));
    const __m128 e2 = _mm_sub_ps(_mm_mul_ps(x[0], y[1]), _mm_mul_ps(y[0], x[1]));
    const __m128 zero = _mm_setzero_ps();
    const __m128 anyZero =
        _mm_and_ps(valid, _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)), _mm_cmpeq_ps(e2, zero)));
    const __m128 anyNeg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)), _mm_cmplt_ps(e2, zero));
    const __m128 anyPos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)), _mm_cmpgt_ps(e2, zero));
    const __m128 det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
    __m128 ok = _mm_andnot_ps(_mm_or_ps(anyZero, _mm_and_ps(anyNeg, anyPos)), valid);
    // Most leaves the ray reaches it passes beside: stop before the distances.
    if ((_mm_movemask_ps(ok) | _mm_movemask_ps(anyZero)) == 0) return -1;
    ok = _mm_and_ps(ok, _mm_cmpneq_ps(det, zero));
    for (int v = 0; v < 3; ++v) z[v] = _mm_mul_ps(z[v], sz_);
    const __m128 tScaled = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e0, z[0]), _mm_mul_ps(e1, z[1])), _mm_mul_ps(e2, z[2]));
    const __m128 tMaxDet = _mm_mul_ps(_mm_set1_ps(tMax), det);
    const __m128 badNeg = _mm_and_ps(_mm_cmplt_ps(det, zero),
                                     _mm_or_ps(_mm_cmpge_ps(tScaled, zero), _mm_cmplt_ps(tScaled, tMaxDet)));
    const __m128 badPos = _mm_and_ps(_mm_cmpgt_ps(det, zero),
                                     _mm_or_ps(_mm_cmple_ps(tScaled, zero), _mm_cmpgt_ps(tScaled, tMaxDet)));
    ok = _mm_andnot_ps(_mm_or_ps(badNeg, badPos), ok);
    int found = -1;
    if (_mm_movemask_ps(ok) != 0) found = nearest<kAnyHit>(ok, e0, e1, e2, det, tScaled, x, y, z, tMax, out);
    if (kAnyHit && found >= 0) return found;
    // Lanes with an edge exactly zero: the scalar test, which recomputes it in double.
    for (int mask = _mm_movemask_ps(anyZero); mask != 0; mask &= mask - 1) {
      const int lane = __builtin_ctz(unsigned(mask));
      if (auto hit = intersectTriangle(TriangleRay<float>(ray_), tMax, leaf.vertex(0, lane), leaf.vertex(1, lane), leaf.vertex(2, lane))) {
        out = *hit;
        tMax = hit->t;
        found = lane;
        if constexpr (kAnyHit) break;
      }
    }
    return found;
  }

 private:
  // pbrt's bound on the error of t for the lanes still in `ok`, then the nearest one.
  template <bool kAnyHit>
  static int nearest(__m128 ok, __m128 e0, __m128 e1, __m128 e2, __m128 det, __m128 tScaled, const __m128 x[3],
                     const __m128 y[3], const __m128 z[3], float& tMax, TriangleIntersection<float>& out) {
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const auto abs = [&](__m128 v) { return _mm_and_ps(v, absMask); };
    const auto max3 = [&](const __m128 v[3]) { return _mm_max_ps(_mm_max_ps(abs(v[0]), abs(v[1])), abs(v[2])); };
    const __m128 invDet = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 t = _mm_mul_ps(tScaled, invDet);
    const __m128 maxZt = max3(z), maxXt = max3(x), maxYt = max3(y);
    const __m128 g2 = _mm_set1_ps(gamma<float>(2)), g3 = _mm_set1_ps(gamma<float>(3)),
                 g5 = _mm_set1_ps(gamma<float>(5));
    const __m128 deltaZ = _mm_mul_ps(g3, maxZt);
    const __m128 deltaX = _mm_mul_ps(g5, _mm_add_ps(maxXt, maxZt));
    const __m128 deltaY = _mm_mul_ps(g5, _mm_add_ps(maxYt, maxZt));
    const __m128 deltaE = _mm_mul_ps(
        _mm_set1_ps(2.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g2, maxXt), maxYt), _mm_mul_ps(deltaY, maxXt)),
                                      _mm_mul_ps(deltaX, maxYt)));
    const __m128 maxE = _mm_max_ps(_mm_max_ps(abs(e0), abs(e1)), abs(e2));
    const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g3, maxE), maxZt), _mm_mul_ps(deltaE, maxZt)),
                                  _mm_mul_ps(deltaZ, maxE));
    const __m128 deltaT = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(3.0f), sum), abs(invDet));
    int mask = _mm_movemask_ps(_mm_and_ps(ok, _mm_cmpgt_ps(t, deltaT)));
    if (mask == 0) return -1;
    alignas(16) float ts[4], b0[4], b1[4], b2[4];
    _mm_store_ps(ts, t);
    _mm_store_ps(b0, _mm_mul_ps(e0, invDet));
    _mm_store_ps(b1, _mm_mul_ps(e1, invDet));
    _mm_store_ps(b2, _mm_mul_ps(e2, invDet));
    int lane = __builtin_ctz(unsigned(mask));
    if constexpr (!kAnyHit) {
      for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
        const int other = __builtin_ctz(unsigned(mask));
        if (ts[other] < ts[lane]) lane = other;
      }
    }
    out = TriangleIntersection<float>{b0[lane], b1[lane], b2[lane], ts[lane]};
    tMax = ts[lane];
    return lane;
  }

  Ray<float> ray_;
  std::ptrdiff_t row_[3];
  __m128 o_[3], sx_, sy_, sz_;
};
}  // namespace

namespace sse {
template <typename T>
using BoxTest = std::conditional_t<std::is_same_v<T, float>, ChildBoxTestSse, ChildBoxTest<T>>;
#include "raytrace/bvh_traverse.inl"
}  // namespace sse

ENGINE_AVX2_BEGIN
namespace avx2 {

// Float rays with AVX2: all eight boxes in one register, as ChildBoxTestSse computes
// each half. Compiled for AVX2 (the pragma above) and run only where the CPU has it;
// inlined into the AVX-512 traversal below as well.
class ChildBoxTestAvx2 : public SimdBoxRows {
 public:
  explicit ChildBoxTestAvx2(const Ray<float>& ray) : SimdBoxRows(ray) {
    for (int axis = 0; axis < 3; ++axis) {
      o_[axis] = _mm256_set1_ps(ray.o[axis]);
      inv_[axis] = _mm256_set1_ps(slabs_.invDir[axis]);
    }
  }

  [[gnu::always_inline]] int operator()(const Bvh::Node& node, float tMax, float tEntry[Bvh::kWidth]) const {
    __m256 t0 = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    __m256 t1 = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    for (int axis = 0; axis < 3; ++axis) {
      const __m256 nearSlab = _mm256_load_ps(rows(node) + near_[axis]);
      const __m256 farSlab = _mm256_load_ps(rows(node) + far_[axis]);
      t0 = _mm256_max_ps(_mm256_mul_ps(_mm256_sub_ps(nearSlab, o_[axis]), inv_[axis]), t0);
      t1 = _mm256_min_ps(_mm256_mul_ps(_mm256_sub_ps(farSlab, o_[axis]), inv_[axis]), t1);
    }
    t1 = _mm256_mul_ps(t1, _mm256_set1_ps(kWiden));
    const __m256 inside =
        _mm256_and_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ), _mm256_cmp_ps(t1, _mm256_setzero_ps(), _CMP_GT_OQ));
    const __m256 hit = _mm256_and_ps(inside, _mm256_cmp_ps(t0, _mm256_set1_ps(tMax), _CMP_LT_OQ));
    _mm256_storeu_ps(tEntry, t0);
    return _mm256_movemask_ps(hit);
  }

 private:
  __m256 o_[3], inv_[3];
};

template <typename T>
using BoxTest = std::conditional_t<std::is_same_v<T, float>, ChildBoxTestAvx2, ChildBoxTest<T>>;
#include "raytrace/bvh_traverse.inl"

int testBoxes(const Bvh::Node& node, const Ray<float>& ray, float tMax, float tEntry[Bvh::kWidth]) {
  return ChildBoxTestAvx2(ray)(node, tMax, tEntry);
}
}  // namespace avx2
ENGINE_AVX2_END

// The same AVX2 code compiled once more with AVX-512VL allowed: the same operations,
// so the same bits (no fused multiply-adds: -ffp-contract=off), but with 32 vector
// registers the ray's origin and inverse direction stay in registers across the
// loop instead of being reloaded for every node, and the three compares fold into
// one ternary logic instruction.
ENGINE_AVX512_BEGIN
namespace avx512 {
template <typename T>
using BoxTest = std::conditional_t<std::is_same_v<T, float>, avx2::ChildBoxTestAvx2, ChildBoxTest<T>>;
#include "raytrace/bvh_traverse.inl"
}  // namespace avx512
ENGINE_AVX512_END

namespace {
Bvh::Isa bestIsa() {
  if (cpuHasAvx512()) return Bvh::Isa::kAvx512;
  return cpuHasAvx2() ? Bvh::Isa::kAvx2 : Bvh::Isa::kSse2;
}
std::atomic<Bvh::Isa> gIsa{bestIsa()};
}  // namespace

Bvh::Isa Bvh::isa() { return gIsa.load(std::memory_order_relaxed); }

void Bvh::setIsa(Isa isa) {
  if ((isa == Isa::kAvx2 && !cpuHasAvx2()) || (isa == Isa::kAvx512 && !cpuHasAvx512())) return;
  gIsa.store(isa, std::memory_order_relaxed);
}

const char* Bvh::isaName(Isa isa) {
  switch (isa) {
    case Isa::kSse2: return "SSE2";
    case Isa::kAvx2: return "AVX2";
    case Isa::kAvx512: return "AVX2 with AVX-512VL";
  }
  return "?";
}

int Bvh::testBoxes(const Node& node, const Ray<float>& ray, float tMax, float tEntry[kWidth]) {
  if (isa() != Isa::kSse2) return avx2::testBoxes(node, ray, tMax, tEntry);
  return ChildBoxTestSse(ray)(node, tMax, tEntry);
}

template <typename T, bool kAnyHit>
bool Bvh::trace(const Ray<T>& ray, BvhHit<T>& hit) const {
  if (triangleCount_ == 0) return false;
  if constexpr (std::is_same_v<T, float>) {
    if (isa() == Isa::kAvx512) return avx512::traverse<T, kAnyHit>(view(), ray, hit);
    if (isa() == Isa::kAvx2) return avx2::traverse<T, kAnyHit>(view(), ray, hit);
  }
  return sse::traverse<T, kAnyHit>(view(), ray, hit);
}

template <typename T>
std::optional<BvhHit<T>> Bvh::intersect(const Ray<T>& ray) const {
  BvhHit<T> hit;
  if (!trace<T, false>(ray, hit)) return std::nullopt;
  return hit;
}

template <typename T>
bool Bvh::intersectAny(const Ray<T>& ray) const {
  BvhHit<T> hit;
  return trace<T, true>(ray, hit);
}

template std::optional<BvhHit<float>> Bvh::intersect(const Ray<float>&) const;
template std::optional<BvhHit<double>> Bvh::intersect(const Ray<double>&) const;
template bool Bvh::intersectAny(const Ray<float>&) const;
template bool Bvh::intersectAny(const Ray<double>&) const;

}  // namespace engine::rt
