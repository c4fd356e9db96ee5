#pragma once
// Rays, bounds and the floating-point error arithmetic that keeps secondary rays from
// hitting the surface they leave (pbrt-v4, "Managing Rounding Error"). Templated on
// the scalar so that the same code runs in float (the default, fast) and in double
// (to measure how much of an image is float error).
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <glm/glm.hpp>
#include <immintrin.h>

namespace engine::rt {

enum class Precision { Float, Double };

template <typename T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

// v / s, the quotients glm's operator/ gives, in one SSE division for float: glm's
// three divisions by one divisor queued on the divider, a bounce's longest wait where
// a direction is normalised by a length it has just taken.
template <typename T>
inline Vec3<T> dividedBy(const Vec3<T>& v, T s) {
  if constexpr (std::is_same_v<T, float>) {
    const __m128 q = _mm_div_ps(_mm_setr_ps(v.x, v.y, v.z, 1.0f), _mm_set1_ps(s));
    return {_mm_cvtss_f32(q), _mm_cvtss_f32(_mm_shuffle_ps(q, q, 1)), _mm_cvtss_f32(_mm_shuffle_ps(q, q, 2))};
  } else {
    return v / s;
  }
}

template <typename T>
struct Ray {
  Vec3<T> o{0};
  Vec3<T> d{0, 0, 1};
  T tMax = std::numeric_limits<T>::infinity();

  Vec3<T> operator()(T t) const { return o + d * t; }
};

// Half an ulp of 1: the bound on the relative error of one rounded operation.
template <typename T>
constexpr T kMachineEpsilon = std::numeric_limits<T>::epsilon() * T(0.5);

// pbrt's gamma(n): bounds the relative error of n chained rounded operations.
template <typename T>
constexpr T gamma(int n) {
  return (T(n) * kMachineEpsilon<T>) / (T(1) - T(n) * kMachineEpsilon<T>);
}

// std::nextafter toward +-infinity, as pbrt-v4's NextFloatUp/Down: a step of the bit
// pattern, inline (libm's nextafterf is a call, three of them per spawned ray). The
// same value as std::nextafter for every input but NaN (ShapesTest.NextUpAndDownAreNextafter).
template <typename T>
T nextUp(T v) {
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  if (std::isinf(v) && v > T(0)) return v;
  if (v == T(0)) v = T(0);  // -0 steps up as +0 does
  const Bits bits = std::bit_cast<Bits>(v);
  return std::bit_cast<T>(v >= T(0) ? bits + 1 : bits - 1);
}
template <typename T>
T nextDown(T v) {
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  if (std::isinf(v) && v < T(0)) return v;
  if (v == T(0)) v = -T(0);
  const Bits bits = std::bit_cast<Bits>(v);
  return std::bit_cast<T>(v > T(0) ? bits - 1 : bits + 1);
}

// Moves a hit point off its surface, along the geometric normal n, to the side that w
// points to, by more than the point's error bound pError (per component). Because the
// bound grows with the magnitudes that produced the point, a surface never shadows or
// reflects into itself, whether it sits at the origin or 1e5 away; no fixed epsilon.
template <typename T>
Vec3<T> offsetRayOrigin(const Vec3<T>& p, const Vec3<T>& pError, const Vec3<T>& n, const Vec3<T>& w) {
  const T d = glm::dot(glm::abs(n), pError);
  Vec3<T> offset = n * d;
  if (glm::dot(w, n) < T(0)) offset = -offset;
  Vec3<T> po = p + offset;
  // The addition above rounds too; step each moved component one more ulp outward.
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > T(0)) {
      po[i] = nextUp(po[i]);
    } else if (offset[i] < T(0)) {
      po[i] = nextDown(po[i]);
    }
  }
  return po;
}

// Axis-aligned bounds in float (the BVH's storage); tested with rays of either
// precision. Float bounds of float vertices are exact, so a double ray loses nothing.
struct Bounds3f {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds3f& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  bool empty() const { return min.x > max.x; }
  glm::vec3 centroid() const { return (min + max) * 0.5f; }
  float surfaceArea() const {
    if (empty()) return 0.0f;
    const glm::vec3 e = max - min;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  int maxExtentAxis() const {
    const glm::vec3 e = max - min;
    return e.x > e.y ? (e.x > e.z ? 0 : 2) : (e.y > e.z ? 1 : 2);
  }
};

// The slab test, written as pbrt's Bounds3::IntersectP: dirIsNeg picks the near and
// far slab per axis, and tMax is widened by 2 gamma(3) so that rounding can never
// make a ray miss a box that holds the triangle it hits. It also gives the entry
// distance t0, so that a traversal can visit the nearer of two boxes first and skip
// a box whose entry lies beyond the nearest hit found since it was pushed. Always inlined:
// it is the traversal's inner loop, and g++ -O2 otherwise calls it (a tenth of the
// demo's tracing time went to the call).
template <typename T>
[[gnu::always_inline]] inline bool intersectBounds(const Bounds3f& b, const Ray<T>& ray, T tMax, const Vec3<T>& invDir, const int dirIsNeg[3],
                     T& tEntry) {
  const glm::vec3* bounds[2] = {&b.min, &b.max};
  T t0 = (T((*bounds[dirIsNeg[0]]).x) - ray.o.x) * invDir.x;
  T t1 = (T((*bounds[1 - dirIsNeg[0]]).x) - ray.o.x) * invDir.x;
  const T ty0 = (T((*bounds[dirIsNeg[1]]).y) - ray.o.y) * invDir.y;
  T ty1 = (T((*bounds[1 - dirIsNeg[1]]).y) - ray.o.y) * invDir.y;
  constexpr T kWiden = T(1) + T(2) * gamma<T>(3);
  t1 *= kWiden;
  // A ray lying in a slab's plane (origin on it, direction 0 along that axis) gives
  // 0 * inf = NaN: it is inside that slab, so the x interval becomes unbounded. NaN in
  // y and z needs nothing, as every comparison below then keeps the x interval.
  if (t0 != t0) t0 = -std::numeric_limits<T>::infinity();
  if (t1 != t1) t1 = std::numeric_limits<T>::infinity();
  ty1 *= kWiden;
  if (t0 > ty1 || ty0 > t1) return false;
  if (ty0 > t0) t0 = ty0;
  if (ty1 < t1) t1 = ty1;
  const T tz0 = (T((*bounds[dirIsNeg[2]]).z) - ray.o.z) * invDir.z;
  T tz1 = (T((*bounds[1 - dirIsNeg[2]]).z) - ray.o.z) * invDir.z;
  tz1 *= kWiden;
  if (t0 > tz1 || tz0 > t1) return false;
  if (tz0 > t0) t0 = tz0;
  if (tz1 < t1) t1 = tz1;
  tEntry = t0;
  return t0 < tMax && t1 > T(0);
}

// The same test without the entry distance.
template <typename T>
inline bool intersectBounds(const Bounds3f& b, const Ray<T>& ray, T tMax, const Vec3<T>& invDir, const int dirIsNeg[3]) {
  T entry;
  return intersectBounds(b, ray, tMax, invDir, dirIsNeg, entry);
}

// A ray's inverse direction and slab order, made once and tested against many boxes.
template <typename T>
struct BoundsRay {
  Vec3<T> invDir;
  int dirIsNeg[3];

  explicit BoundsRay(const Ray<T>& ray) : invDir(T(1) / ray.d) {
    for (int axis = 0; axis < 3; ++axis) dirIsNeg[axis] = invDir[axis] < 0;
  }
  // `ray` is the one given to the constructor, its tMax perhaps shortened since.
  bool hits(const Bounds3f& b, const Ray<T>& ray) const { return intersectBounds(b, ray, ray.tMax, invDir, dirIsNeg); }
};

}  // namespace engine::rt
