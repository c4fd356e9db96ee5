#include "raytrace/whitted_packets.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/brdf.h"
#include "raytrace/avx2_region.h"
#include "raytrace/camera_lanes.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/shape_lanes.h"

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
  p.shapes_ = &scene.shapeLanes();
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
namespace {
namespace camera8 {
using namespace lanes8;

Rays primaryRays(const PinholeCamera& camera, const double* px, const double* py) {
  alignas(32) float dx[kLanes], dy[kLanes], dz[kLanes], tMax[kLanes];
  cameraRays(camera, px, py, dx, dy, dz, tMax);
  Rays r;
  r.o = broadcast(glm::vec3(camera.position()));
  r.d = {_mm256_load_ps(dx), _mm256_load_ps(dy), _mm256_load_ps(dz)};
  r.dd = dot(r.d, r.d);
  r.tMax = _mm256_load_ps(tMax);
  return r;
}

F gather(const std::vector<float>& table, I index) { return _mm256_i32gather_ps(table.data(), index, 4); }

}  // namespace camera8
}  // namespace

void WhittedPackets::trace(const double* px, const double* py, int count, Lanes& out, std::uint64_t& shadowRays) const {
  using namespace lanes8;
  using namespace camera8;
  // Lanes past count repeat the first sample; their answers are dropped.
  alignas(32) double xs[kLanes], ys[kLanes];
  for (int i = 0; i < kLanes; ++i) xs[i] = px[i < count ? i : 0], ys[i] = py[i < count ? i : 0];
  Rays ray = primaryRays(camera_, xs, ys);
  const Shapes scene{*shapes_};
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
