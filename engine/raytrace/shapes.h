#pragma once
// The shapes (pbrt naming): Sphere, Plane and the watertight Triangle test. Each
// Intersect returns the parametric distance of the nearest hit in (0, tMax) as a
// std::optional; Interaction then builds the hit record (point, error bound, normal)
// for the one hit that wins, so the losers cost only the distance test.
#include <algorithm>
#include <cmath>
#include <optional>

#include "raytrace/ray.h"

namespace engine::rt {

template <typename T>
struct SurfaceInteraction {
  Vec3<T> p{0};
  Vec3<T> pError{0};  // bound on |computed p - exact p| per component
  Vec3<T> n{0, 1, 0};   // geometric normal, unit, as the shape defines it
  Vec3<T> ns{0, 1, 0};  // shading normal (interpolated vertex normals), unit
  T t = 0;
  int material = 0;
  glm::vec2 uv{0.0f};  // texture coordinates, as the rasterizer interpolates them
  glm::vec2 uv1{0.0f};  // the second set (glTF TEXCOORD_1; uv where there is none)
  glm::vec4 color{1.0f};  // glTF COLOR_0, interpolated; white where there is none
  // How fast uv changes along the surface: the square root of uv area per unit of
  // surface area (0 where nothing is mapped), to turn a ray cone's width into a
  // texture footprint.
  float uvPerMetre = 0.0f;
  // The triangle's dP/du and dP/dv of its TEXCOORD_0 (zero on shapes and unmapped
  // meshes): the tangent frame KHR_materials_anisotropy is oriented by.
  glm::vec3 dpdu{0.0f}, dpdv{0.0f};

  // A ray leaving this point toward w, offset so that it cannot hit this surface.
  Ray<T> spawnRay(const Vec3<T>& w) const { return Ray<T>{offsetRayOrigin(p, pError, n, w), w}; }
  // A ray toward the point `target`: d = target - origin, so tMax < 1 stops short of it.
  Ray<T> spawnRayTo(const Vec3<T>& target, T tMax) const {
    const Vec3<T> o = offsetRayOrigin(p, pError, n, target - p);
    return Ray<T>{o, target - o, tMax};
  }
};

template <typename T>
struct Sphere {
  Vec3<T> center{0};
  T radius = 1;
  int material = 0;

  // Works in the sphere's frame (o - c first), so a sphere far from the origin costs
  // no more precision than one at it; the discriminant is formed from the distance of
  // the centre to the line (Ray Tracing Gems, ch. 7), not b^2 - 4ac, which cancels
  // catastrophically for small or distant spheres; the roots come from the stable
  // q = -0.5 (b + sign(b) sqrt(disc)): t = q / a and t = c / q.
  std::optional<T> intersect(const Ray<T>& ray) const {
    const Vec3<T> oc = ray.o - center;
    const T a = glm::dot(ray.d, ray.d);
    const T halfB = glm::dot(oc, ray.d);
    const T c = glm::dot(oc, oc) - radius * radius;
    // Outside and moving away: both roots are negative (most shadow and wall rays).
    if (c > T(0) && halfB > T(0)) return std::nullopt;
    const Vec3<T> l = oc - (halfB / a) * ray.d;
    const T dist = glm::length(l);
    const T disc = T(4) * a * ((radius - dist) * (radius + dist));
    if (!(disc >= T(0))) return std::nullopt;
    const T b = T(2) * halfB;
    const T q = T(-0.5) * (b + std::copysign(std::sqrt(disc), b));
    T t0 = q / a;
    T t1 = q != T(0) ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > T(0) && t0 < ray.tMax) return t0;
    if (t1 > T(0) && t1 < ray.tMax) return t1;
    return std::nullopt;
  }

  SurfaceInteraction<T> interaction(const Ray<T>& ray, T t) const {
    SurfaceInteraction<T> si;
    fillInteraction(ray, t, si);
    return si;
  }
  // The same into a default record the caller holds: RtScene fills the one it returns
  // in place, as a record built aside and copied stalled on every hit (its fields'
  // narrow stores read back as wide loads).
  void fillInteraction(const Ray<T>& ray, T t, SurfaceInteraction<T>& si) const {
    si.t = t;
    // Reproject onto the surface: the error is then that of the reprojection only,
    // bounded by the magnitudes of the centre and the radius.
    const Vec3<T> local = ray(t) - center;
    si.n = dividedBy(local, glm::length(local));
    si.p = center + si.n * radius;
    si.pError = gamma<T>(8) * (glm::abs(center) + Vec3<T>(radius));
    si.ns = si.n;
    si.material = material;
  }
};

// The square of a plane that the rasterizer draws: its centre, two unit axes in the
// plane and the half side along them (0: unbounded). A hit off the square misses, so
// that both renderers see the same ground's edge.
struct PlaneSquare {
  glm::dvec3 point{0.0}, axisU{1, 0, 0}, axisV{0, 0, 1};
  double extent = 0.0;

  // Whether the point p of the plane lies on the square, in double: the exact test
  // that every quicker one (ShapePacks' and the lanes' float tests) defers to.
  bool holds(const glm::dvec3& p) const {
    if (extent <= 0.0) return true;
    const glm::dvec3 local = p - point;
    return std::abs(glm::dot(local, axisU)) <= extent && std::abs(glm::dot(local, axisV)) <= extent;
  }
};

// The infinite plane dot(n, p) = d.
template <typename T>
struct Plane {
  Vec3<T> normal{0, 1, 0};
  T d = 0;
  int material = 0;

  std::optional<T> intersect(const Ray<T>& ray) const {
    const T denom = glm::dot(normal, ray.d);
    if (denom == T(0)) return std::nullopt;
    const T t = (d - glm::dot(normal, ray.o)) / denom;
    if (t > T(0) && t < ray.tMax) return t;
    return std::nullopt;
  }

  SurfaceInteraction<T> interaction(const Ray<T>& ray, T t) const {
    SurfaceInteraction<T> si;
    fillInteraction(ray, t, si);
    return si;
  }
  // The same into a default record the caller holds: RtScene fills the one it returns
  // in place, as a record built aside and copied stalled on every hit (its fields'
  // narrow stores read back as wide loads).
  void fillInteraction(const Ray<T>& ray, T t, SurfaceInteraction<T>& si) const {
    si.t = t;
    const Vec3<T> p = ray(t);
    // Reprojecting onto the plane leaves an error of a few roundings of |p| and |d|.
    si.p = p - (glm::dot(normal, p) - d) * normal;
    si.pError = gamma<T>(8) * (glm::abs(si.p) + Vec3<T>(std::abs(d)));
    si.n = normal;
    si.ns = normal;
    si.material = material;
  }
};

template <typename T>
struct TriangleIntersection {
  T b0, b1, b2;  // barycentrics of p0, p1, p2
  T t;
};

namespace detail {

// The 2D edge function a.x b.y - a.y b.x, in T. Watertightness needs the two
// triangles sharing an edge to get signs that agree, not exact values: they evaluate
// the same two products in the opposite order, and round-to-nearest is symmetric, so
// their results are exact negatives of each other (this holds only without fused
// multiply-add, which the build does not enable). A result of zero is ambiguous, and
// edgeFunctionExact settles it.
template <typename T>
T edgeFunction(T ax, T ay, T bx, T by) {
  return ax * by - ay * bx;
}

// In float, evaluated in double: products of floats are exact there, so the result is
// correctly rounded and its sign exact (pbrt-v4's fallback at triangle edges).
template <typename T>
T edgeFunctionExact(T ax, T ay, T bx, T by) {
  if constexpr (sizeof(T) == sizeof(float)) {
    return T(double(ax) * double(by) - double(ay) * double(bx));
  } else {
    return ax * by - ay * bx;
  }
}

template <typename T>
int maxComponentIndex(const Vec3<T>& v) {
  return v.x > v.y ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}

template <typename T>
Vec3<T> permute(const Vec3<T>& v, int x, int y, int z) {
  return Vec3<T>(v[x], v[y], v[z]);
}

}  // namespace detail

// The part of the watertight test that depends on the ray only (the permutation that
// makes the ray's largest direction component z, and the shear to +z), computed once
// per ray by the BVH rather than once per triangle.
template <typename T>
struct TriangleRay {
  Vec3<T> o;
  int kx = 0, ky = 0, kz = 0;
  T sx = 0, sy = 0, sz = 0;

  explicit TriangleRay(const Ray<T>& ray) : o(ray.o) {
    kz = detail::maxComponentIndex(glm::abs(ray.d));
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    const Vec3<T> d = detail::permute(ray.d, kx, ky, kz);
    sx = -d.x / d.z;
    sy = -d.y / d.z;
    sz = T(1) / d.z;
  }
};

// Watertight ray/triangle intersection (Woop, Benthin and Wald, JCGT 2013), as pbrt-v4
// writes it: translate the vertices to the ray origin, permute so the ray's largest
// direction component is z, shear so the ray is +z, then the three 2D edge functions
// decide the hit; points on a shared edge are inside one triangle or the other, never
// neither. The final test rejects t that rounding could have made positive.
template <typename T>
std::optional<TriangleIntersection<T>> intersectTriangle(const TriangleRay<T>& r, T tMax, const Vec3<T>& p0,
                                                         const Vec3<T>& p1, const Vec3<T>& p2) {
  using detail::permute;
  Vec3<T> p0t = permute(p0 - r.o, r.kx, r.ky, r.kz);
  Vec3<T> p1t = permute(p1 - r.o, r.kx, r.ky, r.kz);
  Vec3<T> p2t = permute(p2 - r.o, r.kx, r.ky, r.kz);
  p0t.x += r.sx * p0t.z;
  p0t.y += r.sy * p0t.z;
  p1t.x += r.sx * p1t.z;
  p1t.y += r.sy * p1t.z;
  p2t.x += r.sx * p2t.z;
  p2t.y += r.sy * p2t.z;

  T e0 = detail::edgeFunction(p1t.x, p1t.y, p2t.x, p2t.y);
  T e1 = detail::edgeFunction(p2t.x, p2t.y, p0t.x, p0t.y);
  T e2 = detail::edgeFunction(p0t.x, p0t.y, p1t.x, p1t.y);
  if (sizeof(T) == sizeof(float) && (e0 == 0 || e1 == 0 || e2 == 0)) {
    e0 = detail::edgeFunctionExact(p1t.x, p1t.y, p2t.x, p2t.y);
    e1 = detail::edgeFunctionExact(p2t.x, p2t.y, p0t.x, p0t.y);
    e2 = detail::edgeFunctionExact(p0t.x, p0t.y, p1t.x, p1t.y);
  }
  if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return std::nullopt;
  const T det = e0 + e1 + e2;
  if (det == T(0)) return std::nullopt;

  p0t.z *= r.sz;
  p1t.z *= r.sz;
  p2t.z *= r.sz;
  const T tScaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
  if (det < 0 && (tScaled >= 0 || tScaled < tMax * det)) return std::nullopt;
  if (det > 0 && (tScaled <= 0 || tScaled > tMax * det)) return std::nullopt;

  const T invDet = T(1) / det;
  const T t = tScaled * invDet;

  // pbrt's conservative bound on the error of t: a hit must be farther than it.
  const T maxZt = std::max({std::abs(p0t.z), std::abs(p1t.z), std::abs(p2t.z)});
  const T deltaZ = gamma<T>(3) * maxZt;
  const T maxXt = std::max({std::abs(p0t.x), std::abs(p1t.x), std::abs(p2t.x)});
  const T maxYt = std::max({std::abs(p0t.y), std::abs(p1t.y), std::abs(p2t.y)});
  const T deltaX = gamma<T>(5) * (maxXt + maxZt);
  const T deltaY = gamma<T>(5) * (maxYt + maxZt);
  const T deltaE = T(2) * (gamma<T>(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  const T maxE = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  const T deltaT = T(3) * (gamma<T>(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * std::abs(invDet);
  if (t <= deltaT) return std::nullopt;
  return TriangleIntersection<T>{e0 * invDet, e1 * invDet, e2 * invDet, t};
}

template <typename T>
std::optional<TriangleIntersection<T>> intersectTriangle(const Ray<T>& ray, const Vec3<T>& p0, const Vec3<T>& p1,
                                                         const Vec3<T>& p2) {
  return intersectTriangle(TriangleRay<T>(ray), ray.tMax, p0, p1, p2);
}

// The hit point from barycentrics and its error bound (pbrt: gamma(7) times the sum
// of |b_i p_i|), which grows with the vertices' magnitudes, not with the ray's.
template <typename T>
SurfaceInteraction<T> triangleInteraction(const TriangleIntersection<T>& hit, const Vec3<T>& p0, const Vec3<T>& p1,
                                          const Vec3<T>& p2) {
  SurfaceInteraction<T> si;
  si.t = hit.t;
  si.p = hit.b0 * p0 + hit.b1 * p1 + hit.b2 * p2;
  si.pError = gamma<T>(7) * (glm::abs(hit.b0 * p0) + glm::abs(hit.b1 * p1) + glm::abs(hit.b2 * p2));
  const Vec3<T> n = glm::cross(p1 - p0, p2 - p0);
  const T len = glm::length(n);
  si.n = len > T(0) ? n / len : Vec3<T>(0, 1, 0);
  si.ns = si.n;
  return si;
}

}  // namespace engine::rt
