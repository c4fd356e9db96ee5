#include "raytrace/rt_accel.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <glm/gtc/constants.hpp>

namespace engine::rt {
namespace {

// The rasterizer's sphere (render/mesh.cpp makeSphere): n = (sin t sin p, cos t,
// sin t cos p) at uv = (p / 2 pi, t / pi).
glm::vec2 sphereUv(const glm::dvec3& n) {
  const double theta = std::acos(std::clamp(n.y, -1.0, 1.0));
  double phi = std::atan2(n.x, n.z);
  if (phi < 0.0) phi += 2.0 * glm::pi<double>();
  return glm::vec2(float(phi / (2.0 * glm::pi<double>())), float(theta / glm::pi<double>()));
}

// A per-vertex attribute at a triangle hit, weighted by its barycentrics in float.
template <typename V, typename Hit>
V atHit(const std::vector<V>& values, const Hit& hit, std::uint32_t i0, std::uint32_t i1, std::uint32_t i2) {
  return float(hit.b0) * values[i0] + float(hit.b1) * values[i1] + float(hit.b2) * values[i2];
}

float maxAbs(const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

// The root boxes (RootHits): made as groups and spheres change, tested per ray.
void RtAccel::updateRoots() {
  roots_ = noRoots();
  Bounds3f lanes[Bvh::kWidth];
  float extent = 1.0f;
  const auto grow = [&](const Bounds3f& b) {
    if (b.empty()) return;
    extent = std::max({extent, maxAbs(b.min), maxAbs(b.max)});
  };
  for (std::size_t g = 0; g < groups_.size() && g < std::size_t(kSphereLane); ++g) {
    lanes[g] = groups_[g].bvh.bounds();
    grow(lanes[g]);
  }
  Bounds3f spheres;
  for (const Sphere<float>& s : spheresF_) {
    spheres.extend(s.center - glm::vec3(s.radius));
    spheres.extend(s.center + glm::vec3(s.radius));
  }
  grow(spheres);
  // The float sphere test may accept a ray that passes outside the sphere by its
  // rounding, a few float epsilons of the distances involved (at most the origin's,
  // within the limit, and the sphere's): 2e-5 of the limit is over a hundred times that.
  rootsOriginLimit_ = std::isfinite(extent) ? 16.0f * extent : -1.0f;
  if (!spheres.empty()) {
    const glm::vec3 margin(2e-5f * rootsOriginLimit_);
    spheres.min -= margin;
    spheres.max += margin;
  }
  lanes[kSphereLane] = spheres;
  for (int lane = 0; lane < Bvh::kWidth; ++lane) {
    for (int axis = 0; axis < 3; ++axis) {
      roots_.box[axis][lane] = lanes[lane].min[axis];
      roots_.box[axis + 3][lane] = lanes[lane].max[axis];
    }
  }
}

RtAccel::RootHits RtAccel::testRoots(const Ray<float>& ray) const {
  RootHits hits;
  testRoots(ray, hits);
  return hits;
}

void RtAccel::testRoots(const Ray<float>& ray, RootHits& hits) const {
  hits.mask = Bvh::testBoxes(roots_, ray, ray.tMax, hits.tEntry);
  if (!(maxAbs(ray.o) <= rootsOriginLimit_)) hits.mask |= 1 << kSphereLane;
}

template <>
const std::vector<Sphere<float>>& RtAccel::spheres<float>() const {
  return spheresF_;
}
template <>
const std::vector<Sphere<double>>& RtAccel::spheres<double>() const {
  return spheresD_;
}
template <>
const std::vector<Plane<float>>& RtAccel::planes<float>() const {
  return planesF_;
}
template <>
const std::vector<Plane<double>>& RtAccel::planes<double>() const {
  return planesD_;
}

// Whether a plane's hit at t lies on the square the rasterizer draws (always, for an
// unbounded plane), so that both renderers see the same ground's edge.
template <typename T>
bool RtAccel::onPlaneSquare(std::size_t plane, const Ray<T>& ray, T t) const {
  const PlaneUv& q = planeUvs_[plane];
  if (q.extent <= 0.0) return true;
  if constexpr (std::is_same_v<T, float>) {
    if (packs_.clearlyOnSquare(plane, ray, t)) return true;
  }
  return q.holds(glm::dvec3(ray(t)));
}

template <typename T>
SurfaceInteraction<T> RtAccel::meshInteraction(const Group& group, const BvhHit<T>& hit,
                                               const RtMaterials& materials) const {
  const std::uint32_t meshIndex = group.triangleMesh[hit.triangle];
  const RtMesh& mesh = meshes_[meshIndex];
  const std::size_t first = 3 * std::size_t(hit.triangle - meshFirstTriangle_[meshIndex]);
  const std::uint32_t i0 = mesh.indices[first], i1 = mesh.indices[first + 1], i2 = mesh.indices[first + 2];
  SurfaceInteraction<T> si = triangleInteraction(hit.hit, Vec3<T>(mesh.positions[i0]), Vec3<T>(mesh.positions[i1]),
                                                 Vec3<T>(mesh.positions[i2]));
  if (!mesh.normals.empty()) {
    const Vec3<T> ns = hit.hit.b0 * Vec3<T>(mesh.normals[i0]) + hit.hit.b1 * Vec3<T>(mesh.normals[i1]) +
                       hit.hit.b2 * Vec3<T>(mesh.normals[i2]);
    const T len = glm::length(ns);
    if (len > T(0)) si.ns = ns / len;
  }
  if (!mesh.uvs.empty()) {
    si.uv = atHit(mesh.uvs, hit.hit, i0, i1, i2);
    const glm::vec2 du = mesh.uvs[i1] - mesh.uvs[i0], dv = mesh.uvs[i2] - mesh.uvs[i0];
    const float uvArea = std::abs(du.x * dv.y - du.y * dv.x);
    const float area = glm::length(glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
    si.uvPerMetre = area > 0.0f ? std::sqrt(uvArea / area) : 0.0f;
    const float det = du.x * dv.y - dv.x * du.y;
    if (materials.materials()[size_t(mesh.material)].layers.anisotropy > 0.0f && std::abs(det) > 0.0f) {
      const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0], e2 = mesh.positions[i2] - mesh.positions[i0];
      si.dpdu = (dv.y * e1 - du.y * e2) / det;
      si.dpdv = (du.x * e2 - dv.x * e1) / det;
    }
  }
  si.uv1 = mesh.uvs1.empty() ? si.uv : atHit(mesh.uvs1, hit.hit, i0, i1, i2);
  if (!mesh.colors.empty()) si.color = atHit(mesh.colors, hit.hit, i0, i1, i2);
  si.material = mesh.material;
  return si;
}

template <typename T>
int RtAccel::nearestShape(Ray<T>& ray, std::size_t& index, bool testSpheres) const {
  int kind = 0;
  if constexpr (std::is_same_v<T, float>) {
    if (const int sphere = testSpheres ? packs_.nearestSphere(ray, ray.tMax) : -1; sphere >= 0) {
      kind = 1;
      index = std::size_t(sphere);
    }
    packs_.forEachPlaneHit(ray, ray.tMax, [&](std::size_t plane, float t) {
      if (t < ray.tMax && onPlaneSquare(plane, ray, t)) {
        ray.tMax = t;
        kind = 2;
        index = plane;
      }
      return false;
    });
    return kind;
  }
  const auto& sphereList = spheres<T>();
  for (std::size_t i = 0; i < sphereList.size(); ++i) {
    if (auto t = sphereList[i].intersect(ray)) {
      ray.tMax = *t;
      kind = 1;
      index = i;
    }
  }
  const auto& planeList = planes<T>();
  for (std::size_t i = 0; i < planeList.size(); ++i) {
    if (auto t = planeList[i].intersect(ray); t && onPlaneSquare(i, ray, *t)) {
      ray.tMax = *t;
      kind = 2;
      index = i;
    }
  }
  return kind;
}

template <typename T>
bool RtAccel::anyShape(const Ray<T>& ray, bool testSpheres) const {
  if constexpr (std::is_same_v<T, float>) {
    return (testSpheres && packs_.anySphere(ray)) ||
           packs_.forEachPlaneHit(ray, ray.tMax, [&](std::size_t plane, float t) { return onPlaneSquare(plane, ray, t); });
  }
  for (const auto& s : spheres<T>()) {
    if (s.intersect(ray)) return true;
  }
  const auto& planeList = planes<T>();
  for (std::size_t i = 0; i < planeList.size(); ++i) {
    if (auto t = planeList[i].intersect(ray); t && onPlaneSquare(i, ray, *t)) return true;
  }
  return false;
}

template <typename T>
std::optional<SurfaceInteraction<T>> RtAccel::intersect(const Ray<T>& rayIn, const RtMaterials& materials) const {
  // Member by member: a copy of the whole struct read it back in 16-byte loads over the
  // caller's narrower stores of it, a store-forwarding stall on every ray.
  Ray<T> ray{rayIn.o, rayIn.d, rayIn.tMax};
  // Which shape won: 0 none, 1 sphere, 2 plane; shapes shorten tMax as they hit.
  std::size_t index = 0;
  std::optional<SurfaceInteraction<T>> result;
  if constexpr (std::is_same_v<T, float>) {
    if (boxedTriangles_ && rootsUsable()) {
      const RootHits roots = testRoots(ray);
      const int kind = nearestShape(ray, index, roots.spheres());
      pastShapes(ray, kind, index, result, materials, &roots);
      return result;
    }
  }
  const int kind = nearestShape(ray, index);
  pastShapes(ray, kind, index, result, materials);
  return result;
}

bool RtAccel::onSquareOf(const void* accel, std::size_t plane, const Ray<float>& ray, float t) {
  return static_cast<const RtAccel*>(accel)->onPlaneSquare(plane, ray, t);
}

void RtAccel::intersectMany(const Ray<float>* const* rays, std::size_t count,
                            std::optional<SurfaceInteraction<float>>* out, const RtMaterials& materials) const {
  if (eightRaysAtATime()) {
    for (std::size_t first = 0; first < count; first += lanes8::kLanes) {
      intersectEight(rays + first, int(std::min<std::size_t>(lanes8::kLanes, count - first)), out + first, materials);
    }
    return;
  }
  for (std::size_t first = 0; first < count; first += 4) {
    const int n = int(std::min<std::size_t>(4, count - first));
    ShapePacks::Nearest nearest[4];
    packs_.nearestOfFour(rays + first, n, nearest, onSquareOf, this);
    for (int i = 0; i < n; ++i) {
      const Ray<float>& r = *rays[first + std::size_t(i)];
      Ray<float> ray{r.o, r.d, nearest[i].tMax};
      pastShapes(ray, nearest[i].kind, std::size_t(nearest[i].index), out[first + std::size_t(i)], materials);
    }
  }
}

template <typename T>
void RtAccel::pastShapes(Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result,
                         const RtMaterials& materials, const RootHits* roots) const {
  // Each group's root box is tested against the shortened tMax first, so groups the
  // ray misses, or that lie behind the nearest hit so far, cost one box test rather
  // than a traversal's setup and its root node's eight boxes.
  result.reset();
  if (boxedTriangles_) {  // BoundsRay's three divisions only where there are boxes
    const Group* hitGroup = nullptr;
    std::optional<BvhHit<T>> meshHit;
    const auto visit = [&](const Group& group) {
      if (auto hit = group.bvh.intersect(ray)) {
        ray.tMax = hit->hit.t;
        meshHit = hit;
        hitGroup = &group;
      }
    };
    bool visited = false;
    if constexpr (std::is_same_v<T, float>) {
      if (rootsUsable()) {
        const RootHits own = roots ? RootHits{} : testRoots(ray);
        const RootHits& hits = roots ? *roots : own;
        for (std::size_t g = 0; g < groups_.size(); ++g) {
          if (hits.group(g, ray.tMax)) visit(groups_[g]);
        }
        visited = true;
      }
    }
    if (!visited) {
      const BoundsRay<T> boxes(ray);
      for (const Group& group : groups_) {
        if (boxes.hits(group.bvh.bounds(), ray)) visit(group);
      }
    }
    if (hitGroup) {
      result = meshInteraction(*hitGroup, *meshHit, materials);
      return;
    }
  }
  shapeInteraction(ray, kind, index, result, materials);
}

template <typename T>
void RtAccel::shapeInteraction(const Ray<T>& ray, int kind, std::size_t index,
                               std::optional<SurfaceInteraction<T>>& result, const RtMaterials& materials) const {
  if (kind == 1) {
    SurfaceInteraction<T>& si = result.emplace();
    spheres<T>()[index].fillInteraction(ray, ray.tMax, si);
    shapeUv(kind, index, si, materials);
    return;
  }
  if (kind == 2) {
    SurfaceInteraction<T>& si = result.emplace();
    planes<T>()[index].fillInteraction(ray, ray.tMax, si);
    shapeUv(kind, index, si, materials);
  }
}

void RtAccel::intersectCoherent(std::span<const Ray<float>, Bvh::kPacketSize> rays,
                                std::span<std::optional<SurfaceInteraction<float>>, Bvh::kPacketSize> out,
                                const RtMaterials& materials) const {
  constexpr int kLanes = Bvh::kPacketSize;
  if (!boxedTriangles_ || !rootsUsable()) {
    for (int i = 0; i < kLanes; ++i) out[std::size_t(i)] = intersect(rays[std::size_t(i)], materials);
    return;
  }
  // intersect()'s steps lane by lane, each group's traversal shared: the same roots,
  // shapes and groups in the same order, each lane's tMax shortened as it goes.
  Ray<float> packet[kLanes];
  RootHits roots[kLanes];
  int kind[kLanes];
  std::size_t index[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const Ray<float>& r = rays[std::size_t(i)];
    packet[i] = Ray<float>{r.o, r.d, r.tMax};
    testRoots(packet[i], roots[i]);
  }
  if (cpuHasAvx2()) {
    nearestShapesOfEight(packet, kind, index);
  } else {
    for (int i = 0; i < kLanes; ++i) {
      index[i] = 0;
      kind[i] = nearestShape(packet[i], index[i], roots[i].spheres());
    }
  }
  const Group* hitGroup[kLanes] = {};
  BvhHit<float> meshHit[kLanes];
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    unsigned lanes = 0;
    for (int i = 0; i < kLanes; ++i) lanes |= unsigned(roots[i].group(g, packet[i].tMax)) << i;
    if (lanes == 0) continue;
    const Group& group = groups_[g];
    // Lanes that miss the group's box take no part: with tMax 0 no hit can be theirs.
    Ray<float> entering[kLanes];
    for (int i = 0; i < kLanes; ++i) entering[i] = Ray<float>{packet[i].o, packet[i].d, (lanes >> i & 1) ? packet[i].tMax : 0.0f};
    BvhHit<float> hits[kLanes];
    for (unsigned hit = group.bvh.intersect8(entering, hits) & lanes; hit != 0; hit &= hit - 1) {
      const int i = __builtin_ctz(hit);
      packet[i].tMax = hits[i].hit.t;
      meshHit[i] = hits[i];
      hitGroup[i] = &group;
    }
  }
  for (int i = 0; i < kLanes; ++i) {
    std::optional<SurfaceInteraction<float>>& result = out[std::size_t(i)];
    result.reset();
    if (hitGroup[i]) {
      result = meshInteraction(*hitGroup[i], meshHit[i], materials);
    } else {
      shapeInteraction(packet[i], kind[i], index[i], result, materials);
    }
  }
}

template <typename T>
void RtAccel::shapeUv(int kind, std::size_t index, SurfaceInteraction<T>& si, const RtMaterials& materials) const {
  const float scale = materials.materials()[size_t(si.material)].textureScale;
  const bool readsUv = materials.extras(si.material).readsUv();
  if (kind == 1) {
    if (readsUv) si.uv = sphereUv(glm::dvec3(si.n)) * scale;
    // u runs once around (2 pi r), v from pole to pole (pi r): their geometric mean.
    si.uvPerMetre = scale / (float(std::numbers::pi) * std::sqrt(2.0f) * float(spheres<T>()[index].radius));
  } else {
    if (readsUv) {
      const PlaneUv& q = planeUvs_[index];
      const glm::dvec3 local = glm::dvec3(si.p) - q.point;
      si.uv = glm::vec2(glm::dvec2(glm::dot(local, q.axisU) + q.extent, glm::dot(local, q.axisV) + q.extent) *
                        double(scale));
    }
    si.uvPerMetre = scale;
  }
  si.uv1 = si.uv;
}

ENGINE_AVX2_BEGIN
namespace {

// Eight rays into lanes; lanes past count repeat the first ray. Each lane read as a
// float of its own: vector loads over the rays' (or a staging array's) scalar stores
// would wait for those stores to retire.
lanes8::Rays raysInLanes(const Ray<float>* const* rays, int count) {
  using namespace lanes8;
  const Ray<float>* r[kLanes];
  for (int i = 0; i < kLanes; ++i) r[i] = rays[i < count ? i : 0];
  const auto lanes = [&](auto field) {
    return _mm256_setr_ps(field(*r[0]), field(*r[1]), field(*r[2]), field(*r[3]), field(*r[4]), field(*r[5]),
                          field(*r[6]), field(*r[7]));
  };
  Rays out;
  out.o = {lanes([](const Ray<float>& x) { return x.o.x; }), lanes([](const Ray<float>& x) { return x.o.y; }),
           lanes([](const Ray<float>& x) { return x.o.z; })};
  out.d = {lanes([](const Ray<float>& x) { return x.d.x; }), lanes([](const Ray<float>& x) { return x.d.y; }),
           lanes([](const Ray<float>& x) { return x.d.z; })};
  out.dd = dot(out.d, out.d);
  out.tMax = lanes([](const Ray<float>& x) { return x.tMax; });
  return out;
}

}  // namespace

void RtAccel::nearestShapesOfEight(Ray<float>* rays, int* kind, std::size_t* index) const {
  using namespace lanes8;
  const Ray<float>* lanes[kLanes];
  for (int i = 0; i < kLanes; ++i) lanes[i] = &rays[i];
  Rays r = raysInLanes(lanes, kLanes);
  F t;
  I shape;
  Shapes{lanes_}.nearest(r, t, shape);
  alignas(32) float tMax[kLanes];
  alignas(32) int shapes[kLanes];
  _mm256_store_ps(tMax, t);
  _mm256_store_si256(reinterpret_cast<I*>(shapes), shape);
  for (int i = 0; i < kLanes; ++i) {
    rays[i].tMax = tMax[i];
    const bool sphere = shapes[i] < int(lanes_.spheres);
    kind[i] = shapes[i] < 0 ? 0 : sphere ? 1 : 2;
    index[i] = shapes[i] < 0 ? 0 : std::size_t(shapes[i]) - (sphere ? 0 : lanes_.spheres);
  }
}

void RtAccel::intersectEight(const Ray<float>* const* rays, int count, std::optional<SurfaceInteraction<float>>* out,
                             const RtMaterials& materials) const {
  using namespace lanes8;
  Rays r = raysInLanes(rays, count);
  const Shapes shapes{lanes_};
  F t;
  I shape;
  shapes.nearest(r, t, shape);
  const Hits h = shapes.record(r, t, shape);
  alignas(32) float f[10][kLanes];
  const F columns[10] = {t, h.p.x, h.p.y, h.p.z, h.pError.x, h.pError.y, h.pError.z, h.n.x, h.n.y, h.n.z};
  for (int c = 0; c < 10; ++c) _mm256_store_ps(f[c], columns[c]);
  alignas(32) int index[kLanes], material[kLanes];
  _mm256_store_si256(reinterpret_cast<I*>(index), shape);
  _mm256_store_si256(reinterpret_cast<I*>(material), h.material);
  for (int i = 0; i < count; ++i) {
    out[i].reset();
    if (index[i] < 0) continue;
    SurfaceInteraction<float>& si = out[i].emplace();
    si.t = f[0][i];
    si.p = {f[1][i], f[2][i], f[3][i]};
    si.pError = {f[4][i], f[5][i], f[6][i]};
    si.n = si.ns = {f[7][i], f[8][i], f[9][i]};
    si.material = material[i];
    const std::size_t s = std::size_t(index[i]);
    if (s < lanes_.spheres) {
      shapeUv(1, s, si, materials);
    } else {
      shapeUv(2, s - lanes_.spheres, si, materials);
    }
  }
}
ENGINE_AVX2_END

template <typename T>
bool RtAccel::intersectAny(const Ray<T>& ray) const {
  if constexpr (std::is_same_v<T, float>) {
    if (boxedTriangles_ && rootsUsable()) {
      const RootHits roots = testRoots(ray);
      if (anyShape(ray, roots.spheres())) return true;
      for (std::size_t g = 0; g < groups_.size(); ++g) {
        if (roots.group(g, ray.tMax) && groups_[g].bvh.intersectAny(ray)) return true;
      }
      return false;
    }
  }
  if (anyShape(ray)) return true;
  if (!boxedTriangles_) return false;  // BoundsRay's three divisions, for nothing
  const BoundsRay<T> boxes(ray);
  for (const Group& group : groups_) {
    if (boxes.hits(group.bvh.bounds(), ray) && group.bvh.intersectAny(ray)) return true;
  }
  return false;
}

template std::optional<SurfaceInteraction<float>> RtAccel::intersect(const Ray<float>&, const RtMaterials&) const;
template std::optional<SurfaceInteraction<double>> RtAccel::intersect(const Ray<double>&, const RtMaterials&) const;
template bool RtAccel::intersectAny(const Ray<float>&) const;
template bool RtAccel::intersectAny(const Ray<double>&) const;

}  // namespace engine::rt
