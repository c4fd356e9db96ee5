#pragma once
// The analytic shapes (spheres and planes) in float, tested four at a time with SSE
// (part of every x86-64): structure-of-arrays copies of RtScene's shape lists, so a
// ray meets the course room's 3 spheres in one pass and its 5 planes in two, not one
// std::optional at a time. Each lane runs Sphere<float>::intersect and
// Plane<float>::intersect operation for operation (no fused multiply-add: the library
// builds with -ffp-contract=off), so every lane's distance is the scalar one bit for
// bit, and the nearest of several (the lower index on a tie) is the one the scalar
// loop, which shortens tMax as it goes, would keep.
#include <cstdint>
#include <xmmintrin.h>
#include <vector>

#include "raytrace/shapes.h"

namespace engine::rt {

class ShapePacks {
 public:
  // A plane's square: its centre, and its half side along the plane's axes (0:
  // unbounded).
  struct Square {
    glm::dvec3 point{0.0};
    double extent = 0.0;
  };
  // Per plane: its square's centre in float, the centre's |x| + |y| + |z| and the
  // half side (0: unbounded), for the quick test of nearestOfFour.
  struct SquareLanes {
    float x, y, z, size, extent;
  };
  static SquareLanes squareLanesOf(const Square& square);
  // Rebuilt whenever a shape is added. A hit on a bounded plane is kept if its square
  // holds it, which the caller's test decides (nearestOfFour's `onSquare`) unless it
  // is clearly inside.
  void setSpheres(const std::vector<Sphere<float>>& spheres);
  void setPlanes(const std::vector<Plane<float>>& planes, const std::vector<Square>& squares);

  // The nearest sphere hit in (0, ray.tMax): its index, with tMax shortened to it;
  // -1 (tMax unchanged) when none.
  int nearestSphere(const Ray<float>& ray, float& tMax) const;
  bool anySphere(const Ray<float>& ray) const;

  // Four rays at once, one to a lane (the packs' transpose, for a batch of paths a
  // bounce at a time): for each ray the nearest sphere and plane hit in (0, tMax),
  // which nearestSphere and forEachPlaneHit find for it alone, bit for bit: the
  // lanes run the same operations in the same order, each shape against the lane's
  // tMax as shortened by the shapes before it. Rays past `count` are not read.
  struct Nearest {
    int kind = 0;  // 0 none, 1 sphere, 2 plane
    int index = 0;
    float tMax = 0.0f;  // the ray's, shortened to the hit
  };
  // Whether a hit at t lies on a bounded plane's square; asked only of bounded planes.
  using SquareTest = bool (*)(const void* context, std::size_t plane, const Ray<float>& ray, float t);
  // Whether plane `plane`'s hit at t is inside its square whatever the rounding (the
  // float test of nearestOfFour, for one ray): true settles it, false leaves it to
  // the exact test.
  bool clearlyOnSquare(std::size_t plane, const Ray<float>& ray, float t) const;
  void nearestOfFour(const Ray<float>* const rays[4], int count, Nearest out[4], SquareTest onSquare,
                     const void* context) const;

  // Every plane hit in (0, tMax), as what the caller filters further (the square a
  // plane is bounded to): forEachPlaneHit calls visit(index, t) in index order and
  // stops when it returns true.
  template <typename Visit>
  bool forEachPlaneHit(const Ray<float>& ray, float tMax, Visit&& visit) const {
    const RayLanes lanes(ray);
    for (std::size_t pack = 0; pack < planes_.size(); ++pack) {
      alignas(16) float t[4];
      for (int mask = planeHits(planes_[pack], lanes, tMax, t); mask != 0; mask &= mask - 1) {
        const int lane = __builtin_ctz(unsigned(mask));
        if (visit(4 * pack + std::size_t(lane), t[lane])) return true;
      }
    }
    return false;
  }

 private:
  struct alignas(16) SpherePack {
    float cx[4], cy[4], cz[4], radius[4];
    int count = 0;
  };
  struct alignas(16) PlanePack {
    float nx[4], ny[4], nz[4], d[4];
    int count = 0;
  };
  // The ray's scalars every lane shares, broadcast once. Read from the ray one float
  // at a time: a copy of its arrays was compiled to 8-byte loads, one of which
  // straddled the caller's separate stores of o.z and d.x, a store-forwarding stall
  // on every ray.
  struct RayLanes {
    explicit RayLanes(const Ray<float>& ray);
    __m128 o[3], d[3];
    __m128 dd;  // dot(d, d), as glm sums it
  };
  static int sphereHits(const SpherePack& pack, const RayLanes& ray, float tMax, float t[4]);
  static int planeHits(const PlanePack& pack, const RayLanes& ray, float tMax, float t[4]);

  std::vector<SpherePack> spheres_;
  std::vector<PlanePack> planes_;
  std::size_t sphereCount_ = 0, planeCount_ = 0;
  std::vector<SquareLanes> squares_;
};

}  // namespace engine::rt
