#pragma once
// The analytic shapes against eight float rays at once, one ray to a lane (AVX2): each
// lane runs the scalar Sphere and Plane::intersect's operations in their order, each
// shape against the lane's own tMax as the shapes before it shortened it, so every
// lane's nearest hit, hit record and any-hit answer is the one-ray answer bit for bit
// (the ray tracer is compiled with -ffp-contract=off, and glm's sums are summed here
// as glm sums them). Internal to the ray tracer: the Whitted tracer's packets
// (whitted_packets.cpp) and RtScene::intersectMany (the path tracer's bounces).
#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/avx2_region.h"
#include "raytrace/ray.h"
#include "raytrace/shape_packs.h"
#include "raytrace/shapes.h"

namespace engine::rt {

// The spheres and planes, one table (spheres first), a vector per field so that a
// lane's shape is one gather.
struct ShapeLanes {
  std::vector<float> ax, ay, az, b;  // sphere: centre, radius; plane: normal, d
  std::vector<int> material;
  std::size_t spheres = 0, planes = 0;
  struct Square {
    PlaneSquare exact;
    ShapePacks::SquareLanes quick;  // the float test that settles most hits
  };
  std::vector<Square> squares;  // one per plane
  bool boundedPlanes = false;

  void addSphere(const Sphere<float>& s) {
    insert(spheres, s.center, s.radius, s.material);
    ++spheres;
  }
  void addPlane(const Plane<float>& p, const PlaneSquare& square) {
    insert(spheres + planes, p.normal, p.d, p.material);
    ++planes;
    squares.push_back(Square{square, ShapePacks::squareLanesOf({square.point, square.extent})});
    boundedPlanes = boundedPlanes || square.extent > 0.0;
  }
  std::size_t size() const { return spheres + planes; }

 private:
  void insert(std::size_t at, const glm::vec3& a, float bValue, int m) {
    const auto i = std::ptrdiff_t(at);
    ax.insert(ax.begin() + i, a.x), ay.insert(ay.begin() + i, a.y), az.insert(az.begin() + i, a.z);
    b.insert(b.begin() + i, bValue), material.insert(material.begin() + i, m);
  }
};

ENGINE_AVX2_BEGIN
namespace lanes8 {

using F = __m256;
using I = __m256i;
constexpr int kLanes = 8;
constexpr float kInf = std::numeric_limits<float>::infinity();

inline F set1(float v) { return _mm256_set1_ps(v); }
inline F add(F a, F b) { return _mm256_add_ps(a, b); }
inline F sub(F a, F b) { return _mm256_sub_ps(a, b); }
inline F mul(F a, F b) { return _mm256_mul_ps(a, b); }
inline F div(F a, F b) { return _mm256_div_ps(a, b); }
inline F select(F mask, F a, F b) { return _mm256_blendv_ps(b, a, mask); }
inline F bitAnd(F a, F b) { return _mm256_and_ps(a, b); }
inline F bitOr(F a, F b) { return _mm256_or_ps(a, b); }
inline F andNot(F a, F b) { return _mm256_andnot_ps(a, b); }  // b and not a
inline F greater(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
inline F less(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
inline F absolute(F a) { return _mm256_andnot_ps(set1(-0.0f), a); }
inline F negate(F a) { return _mm256_xor_ps(set1(-0.0f), a); }
// glm::max(a, b), (a < b) ? b : a: maxps(b, a) returns a where they are equal or a is NaN.
inline F glmMax(F a, F b) { return _mm256_max_ps(b, a); }
inline int bits(F mask) { return _mm256_movemask_ps(mask); }
inline F laneMask(int mask) {
  const I bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask), bit), bit));
}

struct V3 {
  F x, y, z;
};
inline V3 add(const V3& a, const V3& b) { return {add(a.x, b.x), add(a.y, b.y), add(a.z, b.z)}; }
inline V3 sub(const V3& a, const V3& b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }
inline V3 mul(const V3& a, F s) { return {mul(a.x, s), mul(a.y, s), mul(a.z, s)}; }
inline V3 mul(const V3& a, const V3& b) { return {mul(a.x, b.x), mul(a.y, b.y), mul(a.z, b.z)}; }
inline V3 div(const V3& a, F s) { return {div(a.x, s), div(a.y, s), div(a.z, s)}; }
inline V3 select(F mask, const V3& a, const V3& b) { return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)}; }
inline V3 broadcast(const glm::vec3& v) { return {set1(v.x), set1(v.y), set1(v.z)}; }
// glm::dot's order: (x + y) + z.
inline F dot(const V3& a, const V3& b) { return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z)); }

// Eight rays, one to a lane.
struct Rays {
  V3 o, d;
  F dd;  // dot(d, d), Sphere::intersect's a
  F tMax;
};

// Sphere<float>::intersect in every lane (shape_packs.cpp's sphereTest, eight wide):
// the lanes of `live` that hit, their distance in tOut.
[[gnu::always_inline]] inline F sphereTest(const Rays& r, const glm::vec3& centre, float radius, F tMax, F live, F& tOut) {
  const F zero = _mm256_setzero_ps();
  const V3 oc = sub(r.o, broadcast(centre));
  const F rad = set1(radius);
  const F halfB = dot(oc, r.d);
  const F c = sub(dot(oc, oc), mul(rad, rad));
  live = andNot(bitAnd(greater(c, zero), greater(halfB, zero)), live);
  tOut = zero;
  if (bits(live) == 0) return live;
  const V3 l = sub(oc, mul(r.d, div(halfB, r.dd)));
  const F dist = _mm256_sqrt_ps(dot(l, l));
  const F disc = mul(mul(set1(4.0f), r.dd), mul(sub(rad, dist), add(rad, dist)));
  live = bitAnd(live, _mm256_cmp_ps(disc, zero, _CMP_GE_OQ));
  if (bits(live) == 0) return live;
  const F b = mul(set1(2.0f), halfB);
  const F root = _mm256_sqrt_ps(disc);
  const F q = mul(set1(-0.5f), add(b, bitOr(absolute(root), bitAnd(set1(-0.0f), b))));
  const F t0 = div(q, r.dd);
  const F t1 = select(_mm256_cmp_ps(q, zero, _CMP_NEQ_UQ), div(c, q), t0);
  const F swap = greater(t0, t1);
  const F nearT = select(swap, t1, t0), farT = select(swap, t0, t1);
  const F nearOk = bitAnd(greater(nearT, zero), less(nearT, tMax));
  const F farOk = bitAnd(greater(farT, zero), less(farT, tMax));
  tOut = select(nearOk, nearT, farT);
  return bitAnd(live, bitOr(nearOk, farOk));
}

// Plane<float>::intersect in every lane.
[[gnu::always_inline]] inline F planeTest(const Rays& r, const glm::vec3& normal, float d, F tMax, F live, F& tOut) {
  const F zero = _mm256_setzero_ps();
  const V3 n = broadcast(normal);
  const F denom = dot(n, r.d);
  tOut = div(sub(set1(d), dot(n, r.o)), denom);
  live = bitAnd(live, _mm256_cmp_ps(denom, zero, _CMP_NEQ_UQ));
  return bitAnd(live, bitAnd(greater(tOut, zero), less(tOut, tMax)));
}

// The ray's point at t in each lane, o + d t.
inline V3 pointAt(const Rays& r, F t) { return add(r.o, mul(r.d, t)); }

// pbrt's nextUp and nextDown (ray.h) in every lane where `mask` is set: one step of
// the bit pattern away from zero's side, +-0 stepping as +0 up and -0 down, the
// infinity in the direction of the step left alone.
[[gnu::always_inline]] inline F stepUp(F v, F mask) {
  const F zero = _mm256_setzero_ps();
  const F w = select(_mm256_cmp_ps(v, zero, _CMP_EQ_OQ), zero, v);
  const I one = _mm256_set1_epi32(1), minusOne = _mm256_set1_epi32(-1);
  const F up = _mm256_cmp_ps(w, zero, _CMP_GE_OQ);
  const F stepped = _mm256_castsi256_ps(
      _mm256_add_epi32(_mm256_castps_si256(w), _mm256_blendv_epi8(minusOne, one, _mm256_castps_si256(up))));
  return select(bitAnd(mask, _mm256_cmp_ps(v, set1(kInf), _CMP_NEQ_UQ)), stepped, v);
}
[[gnu::always_inline]] inline F stepDown(F v, F mask) {
  const F zero = _mm256_setzero_ps();
  const F w = select(_mm256_cmp_ps(v, zero, _CMP_EQ_OQ), set1(-0.0f), v);
  const I one = _mm256_set1_epi32(1), minusOne = _mm256_set1_epi32(-1);
  const F down = _mm256_cmp_ps(w, zero, _CMP_GT_OQ);
  const F stepped = _mm256_castsi256_ps(
      _mm256_add_epi32(_mm256_castps_si256(w), _mm256_blendv_epi8(one, minusOne, _mm256_castps_si256(down))));
  return select(bitAnd(mask, _mm256_cmp_ps(v, set1(-kInf), _CMP_NEQ_UQ)), stepped, v);
}

// offsetRayOrigin in every lane.
[[gnu::always_inline]] inline V3 offsetOrigin(const V3& p, const V3& pError, const V3& n, const V3& w) {
  const F along = dot({absolute(n.x), absolute(n.y), absolute(n.z)}, pError);
  V3 offset = mul(n, along);
  const F flip = less(dot(w, n), _mm256_setzero_ps());
  offset = select(flip, V3{negate(offset.x), negate(offset.y), negate(offset.z)}, offset);
  const V3 po = add(p, offset);
  const F zero = _mm256_setzero_ps();
  const auto moved = [&](F value, F by) {
    return stepDown(stepUp(value, greater(by, zero)), less(by, zero));
  };
  return {moved(po.x, offset.x), moved(po.y, offset.y), moved(po.z, offset.z)};
}

// What the first hit leaves for shading, lane by lane.
struct Hits {
  F hit;        // lanes with a hit
  F t;          // the ray's tMax shortened to it
  I shape;      // into the shape table
  V3 p, pError, n;
  I material;
};

// The table's shapes against eight rays.
struct Shapes {
  const ShapeLanes& shapes;

  glm::vec3 vec(std::size_t i) const { return {shapes.ax[i], shapes.ay[i], shapes.az[i]}; }

  // The lanes of `hit` on plane `plane` whose point at t is on its square, the test
  // RtAccel::onPlaneSquare makes (its float pre-test only ever agrees with this one).
  F onSquare(std::size_t plane, const Rays& r, F t, F hit) const {
    const ShapeLanes::Square& square = shapes.squares[plane];
    if (!shapes.boundedPlanes || square.exact.extent <= 0.0) return hit;
    // ShapePacks::clearlyOnSquare: the lanes inside the square whatever the rounding
    // need no exact test.
    const ShapePacks::SquareLanes& q = square.quick;
    const V3 p = pointAt(r, t);
    const F l1 = add(add(absolute(sub(p.x, set1(q.x))), absolute(sub(p.y, set1(q.y)))), absolute(sub(p.z, set1(q.z))));
    const F clearly = _mm256_cmp_ps(add(l1, mul(set1(1e-5f), add(l1, set1(q.size)))), set1(q.extent), _CMP_LE_OQ);
    if ((bits(hit) & ~bits(clearly)) == 0) return hit;
    alignas(32) float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes], ts[kLanes];
    _mm256_store_ps(ox, r.o.x), _mm256_store_ps(oy, r.o.y), _mm256_store_ps(oz, r.o.z);
    _mm256_store_ps(dx, r.d.x), _mm256_store_ps(dy, r.d.y), _mm256_store_ps(dz, r.d.z), _mm256_store_ps(ts, t);
    int mask = bits(hit);
    for (int m = mask & ~bits(clearly); m != 0; m &= m - 1) {
      const int lane = __builtin_ctz(unsigned(m));
      const glm::vec3 point = glm::vec3(ox[lane], oy[lane], oz[lane]) + glm::vec3(dx[lane], dy[lane], dz[lane]) * ts[lane];
      if (!square.exact.holds(glm::dvec3(point))) mask &= ~(1 << lane);
    }
    return bitAnd(hit, laneMask(mask));
  }

  // RtScene::intersect's shapes for eight rays: each shape against every lane's tMax
  // as the shapes before it shortened it, the lower index kept on a tie.
  void nearest(Rays& r, F& t, I& shape) const {
    shape = _mm256_set1_epi32(-1);
    const F all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    for (std::size_t s = 0; s < shapes.spheres + shapes.planes; ++s) {
      F tHit;
      F hit = s < shapes.spheres ? sphereTest(r, vec(s), shapes.b[s], r.tMax, all, tHit)
                                 : planeTest(r, vec(s), shapes.b[s], r.tMax, all, tHit);
      if (s >= shapes.spheres && bits(hit) != 0) hit = onSquare(s - shapes.spheres, r, tHit, hit);
      if (bits(hit) == 0) continue;
      r.tMax = select(hit, tHit, r.tMax);
      shape = _mm256_blendv_epi8(shape, _mm256_set1_epi32(int(s)), _mm256_castps_si256(hit));
    }
    t = r.tMax;
  }

  // RtScene::intersectAny's shapes for the lanes of `live`: which of them are blocked.
  F blocked(const Rays& r, F live) const {
    F hitAny = _mm256_setzero_ps();
    for (std::size_t s = 0; s < shapes.spheres + shapes.planes; ++s) {
      F tHit;
      F hit = s < shapes.spheres ? sphereTest(r, vec(s), shapes.b[s], r.tMax, live, tHit)
                                 : planeTest(r, vec(s), shapes.b[s], r.tMax, live, tHit);
      if (s >= shapes.spheres && bits(hit) != 0) hit = onSquare(s - shapes.spheres, r, tHit, hit);
      hitAny = bitOr(hitAny, hit);
      live = andNot(hit, live);
      if (bits(live) == 0) break;
    }
    return hitAny;
  }

  // Sphere and Plane::fillInteraction in every lane that hit: the reprojected point,
  // its error bound gamma(8) (|a| + b) and the geometric normal.
  Hits record(const Rays& r, F t, I shape) const {
    Hits h;
    h.t = t;
    h.shape = shape;
    h.hit = _mm256_castsi256_ps(_mm256_cmpgt_epi32(shape, _mm256_set1_epi32(-1)));
    const I index = _mm256_max_epi32(shape, _mm256_setzero_si256());
    const V3 a = {_mm256_i32gather_ps(shapes.ax.data(), index, 4), _mm256_i32gather_ps(shapes.ay.data(), index, 4),
                  _mm256_i32gather_ps(shapes.az.data(), index, 4)};
    const F b = _mm256_i32gather_ps(shapes.b.data(), index, 4);
    h.material = _mm256_i32gather_epi32(shapes.material.data(), index, 4);
    const F sphere = _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(int(shapes.spheres)), index));
    const V3 onRay = pointAt(r, t);
    // Sphere: n = (p - c) / |p - c|, p = c + n r.
    const V3 local = sub(onRay, a);
    const V3 sphereN = div(local, _mm256_sqrt_ps(dot(local, local)));
    const V3 sphereP = add(a, mul(sphereN, b));
    // Plane: p - (n . p - d) n.
    const V3 planeP = sub(onRay, mul(a, sub(dot(a, onRay), b)));
    h.n = select(sphere, sphereN, a);
    h.p = select(sphere, sphereP, planeP);
    const V3 magnitude = select(sphere, a, h.p);
    const F extra = select(sphere, b, absolute(b));
    const F g8 = set1(gamma<float>(8));
    h.pError = {mul(g8, add(absolute(magnitude.x), extra)), mul(g8, add(absolute(magnitude.y), extra)),
                mul(g8, add(absolute(magnitude.z), extra))};
    return h;
  }
};

}  // namespace lanes8
ENGINE_AVX2_END

}  // namespace engine::rt
