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

ShapePacks::RayLanes::RayLanes(const Ray<float>& ray)
    : o{ray.o.x, ray.o.y, ray.o.z}, d{ray.d.x, ray.d.y, ray.d.z}, dd(glm::dot(ray.d, ray.d)) {}

void ShapePacks::setSpheres(const std::vector<Sphere<float>>& spheres) {
  packInto(spheres_, spheres, Sphere<float>{glm::vec3(0.0f), 1.0f, 0},
           [](SpherePack& pack, std::size_t lane, const Sphere<float>& sphere) {
             pack.cx[lane] = sphere.center.x;
             pack.cy[lane] = sphere.center.y;
             pack.cz[lane] = sphere.center.z;
             pack.radius[lane] = sphere.radius;
           });
}

void ShapePacks::setPlanes(const std::vector<Plane<float>>& planes) {
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
  const __m128 zero = _mm_setzero_ps();
  const __m128 dx = _mm_set1_ps(ray.d[0]), dy = _mm_set1_ps(ray.d[1]), dz = _mm_set1_ps(ray.d[2]);
  const __m128 ocx = _mm_sub_ps(_mm_set1_ps(ray.o[0]), _mm_load_ps(pack.cx));
  const __m128 ocy = _mm_sub_ps(_mm_set1_ps(ray.o[1]), _mm_load_ps(pack.cy));
  const __m128 ocz = _mm_sub_ps(_mm_set1_ps(ray.o[2]), _mm_load_ps(pack.cz));
  const __m128 radius = _mm_load_ps(pack.radius);
  const __m128 a = _mm_set1_ps(ray.dd);
  const __m128 halfB = dot3(ocx, ocy, ocz, dx, dy, dz);
  const __m128 c = _mm_sub_ps(dot3(ocx, ocy, ocz, ocx, ocy, ocz), _mm_mul_ps(radius, radius));
  // Outside and moving away: most shadow and wall rays stop here.
  __m128 live = _mm_andnot_ps(_mm_and_ps(_mm_cmpgt_ps(c, zero), _mm_cmpgt_ps(halfB, zero)), filledLanes(pack.count));
  if (_mm_movemask_ps(live) == 0) return 0;
  const __m128 k = _mm_div_ps(halfB, a);
  const __m128 lx = _mm_sub_ps(ocx, _mm_mul_ps(k, dx));
  const __m128 ly = _mm_sub_ps(ocy, _mm_mul_ps(k, dy));
  const __m128 lz = _mm_sub_ps(ocz, _mm_mul_ps(k, dz));
  const __m128 dist = _mm_sqrt_ps(dot3(lx, ly, lz, lx, ly, lz));
  const __m128 disc = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(4.0f), a),
                                 _mm_mul_ps(_mm_sub_ps(radius, dist), _mm_add_ps(radius, dist)));
  live = _mm_and_ps(live, _mm_cmpge_ps(disc, zero));  // false for NaN, as !(disc >= 0)
  if (_mm_movemask_ps(live) == 0) return 0;
  const __m128 b = _mm_mul_ps(_mm_set1_ps(2.0f), halfB);
  const __m128 q = _mm_mul_ps(_mm_set1_ps(-0.5f), _mm_add_ps(b, copySign(_mm_sqrt_ps(disc), b)));
  const __m128 t0 = _mm_div_ps(q, a);
  const __m128 t1 = select(_mm_cmpneq_ps(q, zero), _mm_div_ps(c, q), t0);
  const __m128 swap = _mm_cmpgt_ps(t0, t1);
  const __m128 nearT = select(swap, t1, t0), farT = select(swap, t0, t1);
  const __m128 limit = _mm_set1_ps(tMax);
  const __m128 nearOk = _mm_and_ps(_mm_cmpgt_ps(nearT, zero), _mm_cmplt_ps(nearT, limit));
  const __m128 farOk = _mm_and_ps(_mm_cmpgt_ps(farT, zero), _mm_cmplt_ps(farT, limit));
  _mm_store_ps(t, select(nearOk, nearT, farT));
  return _mm_movemask_ps(_mm_and_ps(live, _mm_or_ps(nearOk, farOk)));
}

// Plane<float>::intersect on four planes.
int ShapePacks::planeHits(const PlanePack& pack, const RayLanes& ray, float tMax, float t[4]) {
  const __m128 zero = _mm_setzero_ps();
  const __m128 nx = _mm_load_ps(pack.nx), ny = _mm_load_ps(pack.ny), nz = _mm_load_ps(pack.nz);
  const __m128 denom = dot3(nx, ny, nz, _mm_set1_ps(ray.d[0]), _mm_set1_ps(ray.d[1]), _mm_set1_ps(ray.d[2]));
  const __m128 along = dot3(nx, ny, nz, _mm_set1_ps(ray.o[0]), _mm_set1_ps(ray.o[1]), _mm_set1_ps(ray.o[2]));
  const __m128 hitT = _mm_div_ps(_mm_sub_ps(_mm_load_ps(pack.d), along), denom);
  // cmpneq is true for a NaN denominator, as !(denom == 0) is.
  const __m128 live = _mm_and_ps(_mm_cmpneq_ps(denom, zero), filledLanes(pack.count));
  const __m128 ok = _mm_and_ps(live, _mm_and_ps(_mm_cmpgt_ps(hitT, zero), _mm_cmplt_ps(hitT, _mm_set1_ps(tMax))));
  _mm_store_ps(t, hitT);
  return _mm_movemask_ps(ok);
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

}  // namespace engine::rt
