#include "raytrace/whitted_packets.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/brdf.h"
#include "raytrace/avx2_region.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

std::optional<WhittedPackets> WhittedPackets::create(const RtScene& scene, const RenderSettings& settings) {
  if (!__builtin_cpu_supports("avx2") || settings.precision != Precision::Float) return std::nullopt;
  if (scene.triangleCount() != 0 || scene.render().shading != Shading::Classic) return std::nullopt;
  if (scene.sphereCount() + scene.planeCount() == 0) return std::nullopt;
  if (scene.hasTransparency() || scene.hasSingleSided() || scene.hasTextures()) return std::nullopt;
  for (const LightDesc& light : scene.lights()) {
    if (light.type != LightType::Point && light.type != LightType::Sun) return std::nullopt;
  }
  WhittedPackets p(PinholeCamera(scene.camera(), settings.width, settings.height));
  for (const Sphere<float>& s : scene.floatSpheres()) {
    p.shapes_.ax.push_back(s.center.x), p.shapes_.ay.push_back(s.center.y), p.shapes_.az.push_back(s.center.z);
    p.shapes_.b.push_back(s.radius), p.shapes_.material.push_back(s.material);
  }
  for (std::size_t i = 0; i < scene.floatPlanes().size(); ++i) {
    const Plane<float>& q = scene.floatPlanes()[i];
    p.shapes_.ax.push_back(q.normal.x), p.shapes_.ay.push_back(q.normal.y), p.shapes_.az.push_back(q.normal.z);
    p.shapes_.b.push_back(q.d), p.shapes_.material.push_back(q.material);
    const RtScene::PlaneSquare& square = scene.planeSquare(i);
    const glm::vec3 centre(square.point);
    p.squares_.push_back(Square{square.point, square.axisU, square.axisV, square.extent, centre,
                                std::abs(centre.x) + std::abs(centre.y) + std::abs(centre.z), float(square.extent)});
    p.boundedPlanes_ = p.boundedPlanes_ || square.extent > 0.0;
  }
  p.shapes_.spheres = scene.floatSpheres().size();
  p.shapes_.planes = scene.floatPlanes().size();
  for (int m = 0; m < int(scene.materials().size()); ++m) {
    if (scene.extras(m).unlit) return std::nullopt;
    // Without textures or terrain layers a material is the same at every hit.
    const HitMaterial h = scene.materialAt(m, HitUv(), 0.0f, 0.0, glm::vec3(0.0f, 1.0f, 0.0f));
    MaterialTable& t = p.materials_;
    t.r.push_back(h.albedo.r), t.g.push_back(h.albedo.g), t.b.push_back(h.albedo.b);
    t.ambient.push_back(h.ambient), t.diffuse.push_back(h.diffuse), t.specular.push_back(h.specular);
    t.shininess.push_back(h.shininess), t.reflection.push_back(h.reflection);
    t.er.push_back(h.emission.r), t.eg.push_back(h.emission.g), t.eb.push_back(h.emission.b);
    p.highlights_ = p.highlights_ || h.specular > 0.0f;
  }
  for (const LightDesc& light : scene.lights()) {
    Light l;
    l.sun = light.type == LightType::Sun;
    l.falloff = light.falloff;
    l.shadows = light.shadows;
    // As Tracer::sampleLight forms them.
    l.position = l.sun ? glm::normalize(Vec3<float>(light.direction)) : Vec3<float>(light.position);
    l.radiance = light.color * light.intensity;
    p.lights_.push_back(l);
  }
  p.mirrors_ = settings.maxDepth > 0;
  return p;
}

ENGINE_AVX2_BEGIN
// Named, as well as anonymous: the unity build puts shape_packs.cpp's helpers of the
// same names (for four lanes) in the same translation unit.
namespace {
namespace lanes8 {

using F = __m256;
using I = __m256i;
constexpr int kLanes = WhittedPackets::kLanes;
constexpr float kInf = std::numeric_limits<float>::infinity();

F set1(float v) { return _mm256_set1_ps(v); }
F add(F a, F b) { return _mm256_add_ps(a, b); }
F sub(F a, F b) { return _mm256_sub_ps(a, b); }
F mul(F a, F b) { return _mm256_mul_ps(a, b); }
F div(F a, F b) { return _mm256_div_ps(a, b); }
F select(F mask, F a, F b) { return _mm256_blendv_ps(b, a, mask); }
F bitAnd(F a, F b) { return _mm256_and_ps(a, b); }
F bitOr(F a, F b) { return _mm256_or_ps(a, b); }
F andNot(F a, F b) { return _mm256_andnot_ps(a, b); }  // b and not a
F greater(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
F less(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
F absolute(F a) { return _mm256_andnot_ps(set1(-0.0f), a); }
F negate(F a) { return _mm256_xor_ps(set1(-0.0f), a); }
// glm::max(a, b), (a < b) ? b : a: maxps(b, a) returns a where they are equal or a is NaN.
F glmMax(F a, F b) { return _mm256_max_ps(b, a); }
int bits(F mask) { return _mm256_movemask_ps(mask); }
F laneMask(int mask) {
  const I bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask), bit), bit));
}

struct V3 {
  F x, y, z;
};
V3 add(const V3& a, const V3& b) { return {add(a.x, b.x), add(a.y, b.y), add(a.z, b.z)}; }
V3 sub(const V3& a, const V3& b) { return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)}; }
V3 mul(const V3& a, F s) { return {mul(a.x, s), mul(a.y, s), mul(a.z, s)}; }
V3 mul(const V3& a, const V3& b) { return {mul(a.x, b.x), mul(a.y, b.y), mul(a.z, b.z)}; }
V3 div(const V3& a, F s) { return {div(a.x, s), div(a.y, s), div(a.z, s)}; }
V3 select(F mask, const V3& a, const V3& b) { return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)}; }
V3 broadcast(const glm::vec3& v) { return {set1(v.x), set1(v.y), set1(v.z)}; }
// glm::dot's order: (x + y) + z.
F dot(const V3& a, const V3& b) { return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z)); }

// Eight rays, one to a lane.
struct Rays {
  V3 o, d;
  F dd;  // dot(d, d), Sphere::intersect's a
  F tMax;
};

// PinholeCamera::generateRay<float> and clippedToFarPlane for four lanes, in double as
// they are: the direction rounded once to float, the far plane's t from that float.
void cameraRays(const PinholeCamera& c, const double* px, const double* py, float* d[3], float* tMax) {
  using D = __m256d;
  const D one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
  const D x = _mm256_mul_pd(
      _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(two, _mm256_loadu_pd(px)), _mm256_set1_pd(double(c.width()))), one),
      _mm256_set1_pd(c.xScale()));
  const D yUnscaled =
      _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(two, _mm256_loadu_pd(py)), _mm256_set1_pd(double(c.height()))), one);
  const D y = _mm256_mul_pd(_mm256_xor_pd(_mm256_set1_pd(-0.0), yUnscaled), _mm256_set1_pd(c.yScale()));
  // glm::normalize(dvec3(x, y, 1)): v * (1 / sqrt(dot(v, v))).
  const D inv = _mm256_div_pd(
      one, _mm256_sqrt_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(one, one))));
  const D lx = _mm256_mul_pd(x, inv), ly = _mm256_mul_pd(y, inv), lz = _mm256_mul_pd(one, inv);
  D depth = _mm256_setzero_pd();
  for (int a = 0; a < 3; ++a) {
    const D world = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(lx, _mm256_set1_pd(c.right()[a])),
                                                _mm256_mul_pd(ly, _mm256_set1_pd(c.up()[a]))),
                                  _mm256_mul_pd(lz, _mm256_set1_pd(c.forward()[a])));
    const __m128 rounded = _mm256_cvtpd_ps(world);
    _mm_storeu_ps(d[a], rounded);
    const D term = _mm256_mul_pd(_mm256_cvtps_pd(rounded), _mm256_set1_pd(c.forward()[a]));
    depth = a == 0 ? term : _mm256_add_pd(depth, term);
  }
  const __m128 clipped = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(c.farPlane()), depth));
  // depth > 0 in 64-bit lanes, packed to 32-bit ones.
  const __m256i ahead64 = _mm256_castpd_si256(_mm256_cmp_pd(depth, _mm256_setzero_pd(), _CMP_GT_OQ));
  const __m128 ahead = _mm_castsi128_ps(
      _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(ahead64, _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0))));
  _mm_storeu_ps(tMax, _mm_blendv_ps(_mm_set1_ps(kInf), clipped, ahead));
}

Rays primaryRays(const PinholeCamera& camera, const double* px, const double* py) {
  alignas(32) float dx[kLanes], dy[kLanes], dz[kLanes], tMax[kLanes];
  for (int half = 0; half < 2; ++half) {
    float* d[3] = {dx + 4 * half, dy + 4 * half, dz + 4 * half};
    cameraRays(camera, px + 4 * half, py + 4 * half, d, tMax + 4 * half);
  }
  Rays r;
  r.o = broadcast(glm::vec3(camera.position()));
  r.d = {_mm256_load_ps(dx), _mm256_load_ps(dy), _mm256_load_ps(dz)};
  r.dd = dot(r.d, r.d);
  r.tMax = _mm256_load_ps(tMax);
  return r;
}

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
V3 pointAt(const Rays& r, F t) { return add(r.o, mul(r.d, t)); }

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

// What the kernel needs of WhittedPackets' tables, passed to the helpers below.
struct Scene {
  const WhittedPackets::ShapeTable& shapes;
  const std::vector<WhittedPackets::Square>& squares;
  bool boundedPlanes;

  glm::vec3 vec(std::size_t i) const { return {shapes.ax[i], shapes.ay[i], shapes.az[i]}; }

  // The lanes of `hit` on plane `plane` whose point at t is on its square, the test
  // RtScene::onPlaneSquare makes (its float pre-test only ever agrees with this one).
  F onSquare(std::size_t plane, const Rays& r, F t, F hit) const {
    const WhittedPackets::Square& q = squares[plane];
    if (!boundedPlanes || q.extent <= 0.0) return hit;
    // ShapePacks::clearlyOnSquare: the lanes inside the square whatever the rounding
    // need no exact test.
    const V3 p = pointAt(r, t);
    const F l1 = add(add(absolute(sub(p.x, set1(q.centre.x))), absolute(sub(p.y, set1(q.centre.y)))),
                     absolute(sub(p.z, set1(q.centre.z))));
    const F clearly = _mm256_cmp_ps(add(l1, mul(set1(1e-5f), add(l1, set1(q.size)))), set1(q.extentF), _CMP_LE_OQ);
    if ((bits(hit) & ~bits(clearly)) == 0) return hit;
    alignas(32) float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes], ts[kLanes];
    _mm256_store_ps(ox, r.o.x), _mm256_store_ps(oy, r.o.y), _mm256_store_ps(oz, r.o.z);
    _mm256_store_ps(dx, r.d.x), _mm256_store_ps(dy, r.d.y), _mm256_store_ps(dz, r.d.z), _mm256_store_ps(ts, t);
    int mask = bits(hit);
    for (int m = mask & ~bits(clearly); m != 0; m &= m - 1) {
      const int lane = __builtin_ctz(unsigned(m));
      const glm::vec3 point = glm::vec3(ox[lane], oy[lane], oz[lane]) + glm::vec3(dx[lane], dy[lane], dz[lane]) * ts[lane];
      const glm::dvec3 local = glm::dvec3(point) - q.point;
      if (!(std::abs(glm::dot(local, q.axisU)) <= q.extent && std::abs(glm::dot(local, q.axisV)) <= q.extent)) {
        mask &= ~(1 << lane);
      }
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

F gather(const std::vector<float>& table, I index) { return _mm256_i32gather_ps(table.data(), index, 4); }

}  // namespace lanes8
}  // namespace

void WhittedPackets::trace(const double* px, const double* py, int count, Lanes& out, std::uint64_t& shadowRays) const {
  using namespace lanes8;
  // Lanes past count repeat the first sample; their answers are dropped.
  alignas(32) double xs[kLanes], ys[kLanes];
  for (int i = 0; i < kLanes; ++i) xs[i] = px[i < count ? i : 0], ys[i] = py[i < count ? i : 0];
  Rays ray = primaryRays(camera_, xs, ys);
  const Scene scene{shapes_, squares_, boundedPlanes_};
  F t;
  I shape;
  scene.nearest(ray, t, shape);
  const Hits h = scene.record(ray, t, shape);
  const F zero = _mm256_setzero_ps();
  const F live = bitAnd(h.hit, laneMask((1 << count) - 1));

  // Tracer::Li: v, the distance, the normal that faces the viewer.
  const F invLength = div(set1(1.0f), _mm256_sqrt_ps(ray.dd));
  const V3 v = mul(ray.d, invLength);
  const F distance = mul(t, _mm256_sqrt_ps(ray.dd));
  const V3 n = select(greater(dot(h.n, v), zero), V3{negate(h.n.x), negate(h.n.y), negate(h.n.z)}, h.n);
  const I material = _mm256_and_si256(h.material, _mm256_castps_si256(h.hit));
  const V3 albedo = {gather(materials_.r, material), gather(materials_.g, material), gather(materials_.b, material)};
  const F diffuse = gather(materials_.diffuse, material);

  // shadeClassic.
  V3 color = mul(albedo, gather(materials_.ambient, material));
  const V3 toEye = {negate(v.x), negate(v.y), negate(v.z)};
  for (const Light& light : lights_) {
    V3 wi, radiance = broadcast(light.radiance);
    Rays shadow;
    if (light.sun) {
      wi = broadcast(light.position);
      shadow.o = offsetOrigin(h.p, h.pError, h.n, wi);
      shadow.d = wi;
      shadow.tMax = set1(kInf);
    } else {
      const V3 target = broadcast(light.position);
      const V3 toLight = sub(target, h.p);
      const F dist2 = dot(toLight, toLight);
      wi = div(toLight, _mm256_sqrt_ps(dist2));
      if (light.falloff) radiance = div(radiance, dist2);
      shadow.o = offsetOrigin(h.p, h.pError, h.n, toLight);
      shadow.d = sub(target, shadow.o);
      shadow.tMax = set1(1.0f);
    }
    F lit = live;
    if (light.shadows) {
      shadow.dd = dot(shadow.d, shadow.d);
      lit = andNot(scene.blocked(shadow, live), live);
      shadowRays += std::uint64_t(__builtin_popcount(unsigned(bits(live))));
    }
    if (bits(lit) == 0) continue;
    // classicReflected without the highlight; lanes with one take the scalar function.
    const F nDotL = glmMax(dot(n, wi), zero);
    V3 reflected = add(mul(albedo, mul(diffuse, nDotL)), V3{zero, zero, zero});
    if (highlights_) {
      alignas(32) float f[3][kLanes], spec[kLanes];
      _mm256_store_ps(spec, gather(materials_.specular, material));
      _mm256_store_ps(f[0], reflected.x), _mm256_store_ps(f[1], reflected.y), _mm256_store_ps(f[2], reflected.z);
      alignas(32) float lanes[12][kLanes];
      const F columns[12] = {n.x, n.y, n.z, toEye.x, toEye.y, toEye.z, wi.x, wi.y, wi.z, albedo.x, albedo.y, albedo.z};
      for (int c = 0; c < 12; ++c) _mm256_store_ps(lanes[c], columns[c]);
      alignas(32) int materials[kLanes];
      _mm256_store_si256(reinterpret_cast<I*>(materials), material);
      for (int m = bits(lit); m != 0; m &= m - 1) {
        const int i = __builtin_ctz(unsigned(m));
        if (spec[i] <= 0.0f) continue;
        const glm::vec3 g = brdf::classicReflected(
            {lanes[0][i], lanes[1][i], lanes[2][i]}, {lanes[3][i], lanes[4][i], lanes[5][i]},
            {lanes[6][i], lanes[7][i], lanes[8][i]}, {lanes[9][i], lanes[10][i], lanes[11][i]},
            materials_.diffuse[std::size_t(materials[i])], spec[i], materials_.shininess[std::size_t(materials[i])]);
        f[0][i] = g.x, f[1][i] = g.y, f[2][i] = g.z;
      }
      reflected = {_mm256_load_ps(f[0]), _mm256_load_ps(f[1]), _mm256_load_ps(f[2])};
    }
    // radiance * visibility (1) * f, where the light is seen.
    color = select(lit, add(color, mul(mul(radiance, set1(1.0f)), reflected)), color);
  }
  color = add(color, V3{gather(materials_.er, material), gather(materials_.eg, material), gather(materials_.eb, material)});

  // The mirror: R = V + 2 N c1 with c1 = -N.V, leaving from the offset point.
  const F share = mirrors_ ? gather(materials_.reflection, material) : zero;
  const F mirrored = bitAnd(live, greater(share, zero));
  V3 r{zero, zero, zero}, ro{zero, zero, zero};
  if (bits(mirrored) != 0) {
    const F c1 = negate(dot(n, v));
    r = add(v, mul(n, mul(set1(2.0f), c1)));
    ro = offsetOrigin(h.p, h.pError, h.n, r);
  }

  out.hits = bits(h.hit) & ((1 << count) - 1);
  _mm256_store_ps(out.dx, ray.d.x), _mm256_store_ps(out.dy, ray.d.y), _mm256_store_ps(out.dz, ray.d.z);
  _mm256_store_ps(out.r, color.x), _mm256_store_ps(out.g, color.y), _mm256_store_ps(out.b, color.z);
  _mm256_store_ps(out.distance, distance), _mm256_store_ps(out.reflection, bitAnd(share, mirrored));
  _mm256_store_ps(out.ox, ro.x), _mm256_store_ps(out.oy, ro.y), _mm256_store_ps(out.oz, ro.z);
  _mm256_store_ps(out.rx, r.x), _mm256_store_ps(out.ry, r.y), _mm256_store_ps(out.rz, r.z);
}

ENGINE_AVX2_END

}  // namespace engine::rt
