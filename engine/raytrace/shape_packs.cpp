#include "raytrace/shape_packs.h"

#include <immintrin.h>

namespace engine::rt {
namespace {

// The lanes of a pack that hold a shape.
__m128 filledLanes(int count) {
  return _mm_castsi128_ps(_mm_cmplt_epi32(_mm_set_epi32(3, 2, 1, 0), _mm_set1_epi32(count)));
}

// mask ? a : b, lane by lane (SSE2 has no blend).
__m128 select(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }

// glm::dot of three lanes' vectors, summed as glm sums it: (x + y) + z.
__m128 dot3(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}

// std::copysign(magnitude, sign).
__m128 copySign(__m128 magnitude, __m128 sign) {
  const __m128 signBit = _mm_set1_ps(-0.0f);
  return _mm_or_ps(_mm_andnot_ps(signBit, magnitude), _mm_and_ps(signBit, sign));
}

// Sphere<float>::intersect lane by lane, whichever side is broadcast (four spheres
// and one ray, or one sphere and four rays): oc = o - centre, d, a = dot(d, d), the
// radius and tMax of each lane. The lanes of `live` with a hit, their distance in tOut.
struct SphereLanesIn {
  __m128 ocx, ocy, ocz, dx, dy, dz, a, radius, tMax;
};
[[gnu::always_inline]] inline __m128 sphereTest(const SphereLanesIn& s, __m128 live, __m128& tOut) {
  const __m128 zero = _mm_setzero_ps();
  tOut = zero;
  const __m128 halfB = dot3(s.ocx, s.ocy, s.ocz, s.dx, s.dy, s.dz);
  const __m128 c = _mm_sub_ps(dot3(s.ocx, s.ocy, s.ocz, s.ocx, s.ocy, s.ocz), _mm_mul_ps(s.radius, s.radius));
  // Outside and moving away: most shadow and wall rays stop here.
  live = _mm_andnot_ps(_mm_and_ps(_mm_cmpgt_ps(c, zero), _mm_cmpgt_ps(halfB, zero)), live);
  if (_mm_movemask_ps(live) == 0) return live;
  const __m128 k = _mm_div_ps(halfB, s.a);
  const __m128 lx = _mm_sub_ps(s.ocx, _mm_mul_ps(k, s.dx));
  const __m128 ly = _mm_sub_ps(s.ocy, _mm_mul_ps(k, s.dy));
  const __m128 lz = _mm_sub_ps(s.ocz, _mm_mul_ps(k, s.dz));
  const __m128 dist = _mm_sqrt_ps(dot3(lx, ly, lz, lx, ly, lz));
  const __m128 disc = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(4.0f), s.a),
                                 _mm_mul_ps(_mm_sub_ps(s.radius, dist), _mm_add_ps(s.radius, dist)));
  live = _mm_and_ps(live, _mm_cmpge_ps(disc, zero));  // false for NaN, as !(disc >= 0)
  if (_mm_movemask_ps(live) == 0) return live;
  const __m128 b = _mm_mul_ps(_mm_set1_ps(2.0f), halfB);
  const __m128 q = _mm_mul_ps(_mm_set1_ps(-0.5f), _mm_add_ps(b, copySign(_mm_sqrt_ps(disc), b)));
  const __m128 t0 = _mm_div_ps(q, s.a);
  const __m128 t1 = select(_mm_cmpneq_ps(q, zero), _mm_div_ps(c, q), t0);
  const __m128 swap = _mm_cmpgt_ps(t0, t1);
  const __m128 nearT = select(swap, t1, t0), farT = select(swap, t0, t1);
  const __m128 nearOk = _mm_and_ps(_mm_cmpgt_ps(nearT, zero), _mm_cmplt_ps(nearT, s.tMax));
  const __m128 farOk = _mm_and_ps(_mm_cmpgt_ps(farT, zero), _mm_cmplt_ps(farT, s.tMax));
  tOut = select(nearOk, nearT, farT);
  return _mm_and_ps(live, _mm_or_ps(nearOk, farOk));
}

// Plane<float>::intersect lane by lane, whichever side is broadcast: the plane's
// normal and d, the ray's origin and direction, tMax. The lanes of `live` with a hit.
struct Lanes3 {
  __m128 x, y, z;
};
struct PlaneLanesIn {
  __m128 nx, ny, nz, d;
};
[[gnu::always_inline]] inline __m128 planeTest(const PlaneLanesIn& p, const Lanes3& o, const Lanes3& d, __m128 tMax, __m128 live, __m128& tOut) {
  const __m128 zero = _mm_setzero_ps();
  const __m128 denom = dot3(p.nx, p.ny, p.nz, d.x, d.y, d.z);
  const __m128 along = dot3(p.nx, p.ny, p.nz, o.x, o.y, o.z);
  tOut = _mm_div_ps(_mm_sub_ps(p.d, along), denom);
  // cmpneq is true for a NaN denominator, as !(denom == 0) is.
  live = _mm_and_ps(live, _mm_cmpneq_ps(denom, zero));
  return _mm_and_ps(live, _mm_and_ps(_mm_cmpgt_ps(tOut, zero), _mm_cmplt_ps(tOut, tMax)));
}

// Shapes four to a pack, lane by lane (`write` copies one shape into a lane). Lanes
// past the last shape hold `filler`, which keeps their arithmetic finite; filledLanes
// drops them.
template <typename Pack, typename Shape, typename Write>
void packInto(std::vector<Pack>& packs, const std::vector<Shape>& shapes, const Shape& filler, Write write) {
  packs.assign((shapes.size() + 3) / 4, Pack{});
  for (std::size_t i = 0; i < 4 * packs.size(); ++i) {
    Pack& pack = packs[i / 4];
    write(pack, i % 4, i < shapes.size() ? shapes[i] : filler);
    pack.count += i < shapes.size() ? 1 : 0;
  }
}

}  // namespace

ShapePacks::SquareLanes ShapePacks::squareLanesOf(const Square& square) {
  const glm::vec3 c(square.point);
  return {c.x, c.y, c.z, std::abs(c.x) + std::abs(c.y) + std::abs(c.z), float(square.extent)};
}

ShapePacks::RayLanes::RayLanes(const Ray<float>& ray)
    : o{_mm_set1_ps(ray.o.x), _mm_set1_ps(ray.o.y), _mm_set1_ps(ray.o.z)},
      d{_mm_set1_ps(ray.d.x), _mm_set1_ps(ray.d.y), _mm_set1_ps(ray.d.z)},
      dd(_mm_set1_ps(glm::dot(ray.d, ray.d))) {}

void ShapePacks::setSpheres(const std::vector<Sphere<float>>& spheres) {
  sphereCount_ = spheres.size();
  packInto(spheres_, spheres, Sphere<float>{glm::vec3(0.0f), 1.0f, 0},
           [](SpherePack& pack, std::size_t lane, const Sphere<float>& sphere) {
             pack.cx[lane] = sphere.center.x;
             pack.cy[lane] = sphere.center.y;
             pack.cz[lane] = sphere.center.z;
             pack.radius[lane] = sphere.radius;
           });
}

void ShapePacks::setPlanes(const std::vector<Plane<float>>& planes, const std::vector<Square>& squares) {
  planeCount_ = planes.size();
  squares_.clear();
  for (const Square& q : squares) squares_.push_back(squareLanesOf(q));
  packInto(planes_, planes, Plane<float>{glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, 0},
           [](PlanePack& pack, std::size_t lane, const Plane<float>& plane) {
             pack.nx[lane] = plane.normal.x;
             pack.ny[lane] = plane.normal.y;
             pack.nz[lane] = plane.normal.z;
             pack.d[lane] = plane.d;
           });
}

// Sphere<float>::intersect on four spheres; see there for why each step is as it is.
int ShapePacks::sphereHits(const SpherePack& pack, const RayLanes& ray, float tMax, float t[4]) {
  const __m128 ocx = _mm_sub_ps(ray.o[0], _mm_load_ps(pack.cx));
  const __m128 ocy = _mm_sub_ps(ray.o[1], _mm_load_ps(pack.cy));
  const __m128 ocz = _mm_sub_ps(ray.o[2], _mm_load_ps(pack.cz));
  __m128 hitT;
  const __m128 hit = sphereTest({ocx, ocy, ocz, ray.d[0], ray.d[1], ray.d[2], ray.dd, _mm_load_ps(pack.radius),
                                 _mm_set1_ps(tMax)},
                                filledLanes(pack.count), hitT);
  _mm_store_ps(t, hitT);
  return _mm_movemask_ps(hit);
}

// Plane<float>::intersect on four planes.
int ShapePacks::planeHits(const PlanePack& pack, const RayLanes& ray, float tMax, float t[4]) {
  __m128 hitT;
  const __m128 hit = planeTest({_mm_load_ps(pack.nx), _mm_load_ps(pack.ny), _mm_load_ps(pack.nz), _mm_load_ps(pack.d)},
                               {ray.o[0], ray.o[1], ray.o[2]}, {ray.d[0], ray.d[1], ray.d[2]},
                               _mm_set1_ps(tMax), filledLanes(pack.count), hitT);
  _mm_store_ps(t, hitT);
  return _mm_movemask_ps(hit);
}

int ShapePacks::nearestSphere(const Ray<float>& ray, float& tMax) const {
  const RayLanes lanes(ray);
  int nearest = -1;
  for (std::size_t pack = 0; pack < spheres_.size(); ++pack) {
    alignas(16) float t[4];
    for (int mask = sphereHits(spheres_[pack], lanes, tMax, t); mask != 0; mask &= mask - 1) {
      const int lane = __builtin_ctz(unsigned(mask));
      // Strictly nearer: of equal distances the lower index stays, as in the scalar loop.
      if (t[lane] < tMax) {
        tMax = t[lane];
        nearest = int(4 * pack) + lane;
      }
    }
  }
  return nearest;
}

bool ShapePacks::anySphere(const Ray<float>& ray) const {
  const RayLanes lanes(ray);
  for (const SpherePack& pack : spheres_) {
    alignas(16) float t[4];
    if (sphereHits(pack, lanes, ray.tMax, t) != 0) return true;
  }
  return false;
}

namespace {

// Four rays, one to a lane, and what each has found so far.
struct RayQuad {
  __m128 ox, oy, oz, dx, dy, dz, dd;
  __m128 tMax;
  __m128i kind = _mm_setzero_si128(), index = _mm_setzero_si128();

  explicit RayQuad(const Ray<float>* const rays[4])
      : ox(_mm_setr_ps(rays[0]->o.x, rays[1]->o.x, rays[2]->o.x, rays[3]->o.x)),
        oy(_mm_setr_ps(rays[0]->o.y, rays[1]->o.y, rays[2]->o.y, rays[3]->o.y)),
        oz(_mm_setr_ps(rays[0]->o.z, rays[1]->o.z, rays[2]->o.z, rays[3]->o.z)),
        dx(_mm_setr_ps(rays[0]->d.x, rays[1]->d.x, rays[2]->d.x, rays[3]->d.x)),
        dy(_mm_setr_ps(rays[0]->d.y, rays[1]->d.y, rays[2]->d.y, rays[3]->d.y)),
        dz(_mm_setr_ps(rays[0]->d.z, rays[1]->d.z, rays[2]->d.z, rays[3]->d.z)),
        dd(dot3(dx, dy, dz, dx, dy, dz)),
        tMax(_mm_setr_ps(rays[0]->tMax, rays[1]->tMax, rays[2]->tMax, rays[3]->tMax)) {}

  // The lanes in `hit` take t and the shape.
  void keep(__m128 hit, __m128 t, int shapeKind, int shapeIndex) {
    tMax = select(hit, t, tMax);
    const __m128i h = _mm_castps_si128(hit);
    kind = _mm_or_si128(_mm_and_si128(h, _mm_set1_epi32(shapeKind)), _mm_andnot_si128(h, kind));
    index = _mm_or_si128(_mm_and_si128(h, _mm_set1_epi32(shapeIndex)), _mm_andnot_si128(h, index));
  }
};

// sphereHits with the shape broadcast and the rays in lanes, each lane's limit its own
// tMax: the scalar Sphere<float>::intersect of every lane.
__m128 sphereLanes(const RayQuad& q, float cx, float cy, float cz, float r, __m128& tOut) {
  const __m128 ocx = _mm_sub_ps(q.ox, _mm_set1_ps(cx));
  const __m128 ocy = _mm_sub_ps(q.oy, _mm_set1_ps(cy));
  const __m128 ocz = _mm_sub_ps(q.oz, _mm_set1_ps(cz));
  const __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
  return sphereTest({ocx, ocy, ocz, q.dx, q.dy, q.dz, q.dd, _mm_set1_ps(r), q.tMax}, all, tOut);
}

// planeHits with the plane broadcast and the rays in lanes.
__m128 planeLanes(const RayQuad& q, float nx, float ny, float nz, float d, __m128& tOut) {
  const __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
  return planeTest({_mm_set1_ps(nx), _mm_set1_ps(ny), _mm_set1_ps(nz), _mm_set1_ps(d)}, {q.ox, q.oy, q.oz},
                   {q.dx, q.dy, q.dz}, q.tMax, all, tOut);
}

// The lanes whose hit at t is inside the square whatever the rounding: |p - centre|
// summed over the axes, in float, bounds the distance along either of the square's
// unit axes; 1e-5 of it and of the centre's size covers float's rounding (a few parts
// in 1e7) with room to spare, so a lane kept here is one the exact test keeps.
// ShapePacks::clearlyOnSquare is the same test for one ray, inside the caller's
// onSquare; four lanes at once here measured 1.03x the path tracer's rate over asking
// it lane by lane (the lanes it leaves, near an edge or outside, run it again there).
int clearlyOnSquareLanes(const RayQuad& q, const ShapePacks::SquareLanes& square, __m128 t) {
  const __m128 signBit = _mm_set1_ps(-0.0f);
  const auto absDiff = [&](__m128 o, __m128 d, float c) {
    return _mm_andnot_ps(signBit, _mm_sub_ps(_mm_add_ps(o, _mm_mul_ps(d, t)), _mm_set1_ps(c)));
  };
  const __m128 l1 = _mm_add_ps(_mm_add_ps(absDiff(q.ox, q.dx, square.x), absDiff(q.oy, q.dy, square.y)),
                               absDiff(q.oz, q.dz, square.z));
  const __m128 margin = _mm_mul_ps(_mm_set1_ps(1e-5f), _mm_add_ps(l1, _mm_set1_ps(square.size)));
  return _mm_movemask_ps(_mm_cmple_ps(_mm_add_ps(l1, margin), _mm_set1_ps(square.extent)));
}

}  // namespace

bool ShapePacks::clearlyOnSquare(std::size_t plane, const Ray<float>& ray, float t) const {
  const SquareLanes& q = squares_[plane];
  const glm::vec3 p = ray(t);
  const float l1 = std::abs(p.x - q.x) + std::abs(p.y - q.y) + std::abs(p.z - q.z);
  return l1 + 1e-5f * (l1 + q.size) <= q.extent;
}

void ShapePacks::nearestOfFour(const Ray<float>* const rays[4], int count, Nearest out[4], SquareTest onSquare,
                               const void* context) const {
  // Lanes past count repeat the first ray; their answers are dropped.
  const Ray<float>* lanes[4];
  for (int i = 0; i < 4; ++i) lanes[i] = rays[i < count ? i : 0];
  RayQuad q(lanes);
  for (std::size_t s = 0; s < sphereCount_; ++s) {
    const SpherePack& p = spheres_[s / 4];
    const std::size_t l = s % 4;
    __m128 t;
    const __m128 hit = sphereLanes(q, p.cx[l], p.cy[l], p.cz[l], p.radius[l], t);
    if (_mm_movemask_ps(hit) != 0) q.keep(hit, t, 1, int(s));
  }
  for (std::size_t i = 0; i < planeCount_; ++i) {
    const PlanePack& p = planes_[i / 4];
    const std::size_t l = i % 4;
    __m128 t;
    __m128 hit = planeLanes(q, p.nx[l], p.ny[l], p.nz[l], p.d[l], t);
    int mask = _mm_movemask_ps(hit);
    if (mask != 0 && squares_[i].extent > 0.0f) {
      alignas(16) float ts[4];
      _mm_store_ps(ts, t);
      // Only the hits not clearly inside the square ask the caller's exact test.
      for (int m = mask & ~clearlyOnSquareLanes(q, squares_[i], t); m != 0; m &= m - 1) {
        const int lane = __builtin_ctz(unsigned(m));
        if (!onSquare(context, i, *lanes[lane], ts[lane])) mask &= ~(1 << lane);
      }
      hit = _mm_castsi128_ps(_mm_cmpgt_epi32(
          _mm_and_si128(_mm_set1_epi32(mask), _mm_setr_epi32(1, 2, 4, 8)), _mm_setzero_si128()));
    }
    if (mask != 0) q.keep(hit, t, 2, int(i));
  }
  alignas(16) float tMax[4];
  alignas(16) int kind[4], index[4];
  _mm_store_ps(tMax, q.tMax);
  _mm_store_si128(reinterpret_cast<__m128i*>(kind), q.kind);
  _mm_store_si128(reinterpret_cast<__m128i*>(index), q.index);
  for (int i = 0; i < count; ++i) out[i] = Nearest{kind[i], index[i], tMax[i]};
}

}  // namespace engine::rt
