#include "raytrace/whitted_packets.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/brdf.h"
#include "raytrace/avx2_region.h"
#include "raytrace/camera_lanes.h"
#include "raytrace/render_types.h"
#include "raytrace/rt_scene.h"
#include "raytrace/shape_lanes.h"

namespace engine::rt {

const char* WhittedPackets::unsupported(const RtScene& scene, const RenderSettings& settings) {
  if (!cpuHasAvx2()) return "the CPU has no AVX2";
  if (settings.precision != Precision::Float) return "double precision";
  if (scene.triangleCount() != 0) return "triangles";
  if (scene.sphereCount() + scene.planeCount() == 0) return "no spheres or planes";
  if (scene.render().shading != Shading::Classic) return "PBR shading";
  if (scene.hasTransparency() || scene.hasSingleSided()) return "transparent or single-sided materials";
  if (scene.hasTextures()) return "textures";
  for (const LightDesc& light : scene.lights()) {
    if (light.type == LightType::Spot) return "a spot light";
  }
  for (int m = 0; m < int(scene.materials().size()); ++m) {
    if (scene.extras(m).unlit) return "an unlit material";
  }
  return nullptr;
}

std::optional<WhittedPackets> WhittedPackets::create(const RtScene& scene, const RenderSettings& settings) {
  if (unsupported(scene, settings)) return std::nullopt;
  WhittedPackets p(PinholeCamera(scene.camera(), settings.width, settings.height));
  p.shapes_ = &scene.shapeLanes();
  for (int m = 0; m < int(scene.materials().size()); ++m) {
    // Without textures or terrain layers a material is the same at every hit.
    const HitMaterial h = scene.materialAt(m, HitUv(), 0.0f, 0.0, glm::vec3(0.0f, 1.0f, 0.0f));
    MaterialTable& t = p.materials_;
    t.r.push_back(h.albedo.r), t.g.push_back(h.albedo.g), t.b.push_back(h.albedo.b);
    t.ambient.push_back(h.ambient), t.diffuse.push_back(h.diffuse), t.specular.push_back(h.specular);
    t.shininess.push_back(h.shininess), t.reflection.push_back(h.reflection);
    t.er.push_back(h.emission.r), t.eg.push_back(h.emission.g), t.eb.push_back(h.emission.b);
  }
  for (const LightDesc& light : scene.lights()) {
    Light l;
    l.type = light.type;
    l.falloff = light.falloff;
    l.shadows = light.shadows;
    // As Tracer::sampleLight forms them.
    l.position = l.type == LightType::Sun ? glm::normalize(Vec3<float>(light.direction)) : Vec3<float>(light.position);
    l.radiance = light.color * light.intensity;
    l.edgeU = Vec3<float>(light.edgeU), l.edgeV = Vec3<float>(light.edgeV);
    p.lights_.push_back(l);
  }
  p.mirrors_ = settings.maxDepth > 0;
  p.shadowSamples_ = std::max(1, settings.shadowSamples);
  return p;
}

ENGINE_AVX2_BEGIN
namespace {
namespace whitted8 {
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

// What Tracer::Li knows of a hit before its lights, lane by lane.
struct Surface {
  const Hits& hit;
  F live;      // the lanes with a hit, of the samples asked for
  V3 n;        // the shading normal, turned to the viewer
  V3 toEye;
  I material;
  V3 albedo;
  F diffuse;
};

// classicReflected where the light is seen (`lit`): albedo * diffuse * N.L in the
// lanes, plus the highlight where a lane's material has one (the scalar function, for
// its pow).
V3 reflectedLanes(const WhittedPackets::MaterialTable& materials, const Surface& s, const V3& wi, F lit) {
  const F zero = _mm256_setzero_ps();
  const F nDotL = glmMax(dot(s.n, wi), zero);
  const V3 f = add(mul(s.albedo, mul(s.diffuse, nDotL)), V3{zero, zero, zero});
  alignas(32) float spec[kLanes];
  _mm256_store_ps(spec, gather(materials.specular, s.material));
  int highlighted = 0;
  for (int i = 0; i < kLanes; ++i) highlighted |= spec[i] > 0.0f ? 1 << i : 0;
  if ((highlighted &= bits(lit)) == 0) return f;
  alignas(32) float lanes[15][kLanes];
  const F columns[15] = {s.n.x,  s.n.y,  s.n.z,      s.toEye.x,  s.toEye.y,  s.toEye.z, wi.x, wi.y,
                         wi.z,   s.albedo.x, s.albedo.y, s.albedo.z, f.x,        f.y,       f.z};
  for (int c = 0; c < 15; ++c) _mm256_store_ps(lanes[c], columns[c]);
  alignas(32) int material[kLanes];
  _mm256_store_si256(reinterpret_cast<I*>(material), s.material);
  for (int m = highlighted; m != 0; m &= m - 1) {
    const int i = __builtin_ctz(unsigned(m));
    const auto k = std::size_t(material[i]);
    const glm::vec3 g = brdf::classicReflected({lanes[0][i], lanes[1][i], lanes[2][i]}, {lanes[3][i], lanes[4][i], lanes[5][i]},
                                               {lanes[6][i], lanes[7][i], lanes[8][i]}, {lanes[9][i], lanes[10][i], lanes[11][i]},
                                               materials.diffuse[k], spec[i], materials.shininess[k]);
    lanes[12][i] = g.x, lanes[13][i] = g.y, lanes[14][i] = g.z;
  }
  return {_mm256_load_ps(lanes[12]), _mm256_load_ps(lanes[13]), _mm256_load_ps(lanes[14])};
}

// The share of an area light's N x N stratified, jittered points each lane sees
// (Tracer::areaVisibility): each live lane draws its points from its own stream.
F areaVisibility(const WhittedPackets::Light& light, int n, const Shapes& shapes, const Surface& s, Pcg32* rngs,
                 std::uint64_t& shadowRays) {
  const Hits& h = s.hit;
  const F one = set1(1.0f);
  F visible = _mm256_setzero_ps();
  const int live = bits(s.live);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      alignas(32) float u[kLanes] = {}, w[kLanes] = {};
      for (int m = live; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(unsigned(m));
        u[k] = (float(i) + rngs[k].uniform()) / float(n) - 0.5f;
        w[k] = (float(j) + rngs[k].uniform()) / float(n) - 0.5f;
      }
      const V3 target = add(add(broadcast(light.position), mul(broadcast(light.edgeU), _mm256_load_ps(u))),
                            mul(broadcast(light.edgeV), _mm256_load_ps(w)));
      Rays shadow;
      shadow.o = offsetOrigin(h.p, h.pError, h.n, sub(target, h.p));
      shadow.d = sub(target, shadow.o);
      shadow.dd = dot(shadow.d, shadow.d);
      shadow.tMax = one;
      visible = add(visible, andNot(shapes.blocked(shadow, s.live), one));
      shadowRays += std::uint64_t(__builtin_popcount(unsigned(live)));
    }
  }
  return div(visible, set1(float(n * n)));
}

// Tracer::sampleLight and shadeClassic's term for one light: its direction and
// radiance at the hit, the shadow rays' verdict, and colour + radiance * visibility *
// f where the light is seen.
V3 addLight(const WhittedPackets::MaterialTable& materials, const WhittedPackets::Light& light, int areaSamples,
            const Shapes& shapes, const Surface& s, Pcg32* rngs, V3 color, std::uint64_t& shadowRays) {
  const Hits& h = s.hit;
  V3 wi, radiance = broadcast(light.radiance);
  Rays shadow{};  // a point or a sun light's one shadow ray
  F visibility = set1(1.0f);
  if (light.type == LightType::Sun) {
    wi = broadcast(light.position);
    shadow.o = offsetOrigin(h.p, h.pError, h.n, wi);
    shadow.d = wi;
    shadow.tMax = set1(kInf);
  } else if (light.type == LightType::Point) {
    const V3 target = broadcast(light.position);
    const V3 toLight = sub(target, h.p);
    const F dist2 = dot(toLight, toLight);
    wi = div(toLight, _mm256_sqrt_ps(dist2));
    if (light.falloff) radiance = div(radiance, dist2);
    shadow.o = offsetOrigin(h.p, h.pError, h.n, toLight);
    shadow.d = sub(target, shadow.o);
    shadow.tMax = set1(1.0f);
  } else {  // area: toward its centre, glm::normalize's v * (1 / |v|)
    const V3 toCentre = sub(broadcast(light.position), h.p);
    wi = mul(toCentre, div(set1(1.0f), _mm256_sqrt_ps(dot(toCentre, toCentre))));
  }
  F lit = s.live;
  if (light.shadows && light.type == LightType::Area) {
    visibility = areaVisibility(light, areaSamples, shapes, s, rngs, shadowRays);
    lit = bitAnd(s.live, greater(visibility, _mm256_setzero_ps()));
  } else if (light.shadows) {
    shadow.dd = dot(shadow.d, shadow.d);
    lit = andNot(shapes.blocked(shadow, s.live), s.live);
    shadowRays += std::uint64_t(__builtin_popcount(unsigned(bits(s.live))));
  }
  if (bits(lit) == 0) return color;
  return select(lit, add(color, mul(mul(radiance, visibility), reflectedLanes(materials, s, wi, lit))), color);
}

}  // namespace whitted8
}  // namespace

void WhittedPackets::trace(const double* px, const double* py, int count, Pcg32* rngs, Lanes& out,
                           std::uint64_t& shadowRays) const {
  using namespace whitted8;
  // Lanes past count repeat the first sample; their answers are dropped.
  alignas(32) double xs[kLanes], ys[kLanes];
  for (int i = 0; i < kLanes; ++i) xs[i] = px[i < count ? i : 0], ys[i] = py[i < count ? i : 0];
  Rays ray = primaryRays(camera_, xs, ys);
  const Shapes shapes{*shapes_};
  F t;
  I shape;
  shapes.nearest(ray, t, shape);
  const Hits h = shapes.record(ray, t, shape);
  const F zero = _mm256_setzero_ps();

  // Tracer::Li: v, the distance, the normal that faces the viewer, the material.
  const V3 v = mul(ray.d, div(set1(1.0f), _mm256_sqrt_ps(ray.dd)));
  const F distance = mul(t, _mm256_sqrt_ps(ray.dd));
  const I material = _mm256_and_si256(h.material, _mm256_castps_si256(h.hit));
  const Surface s{h,
                  bitAnd(h.hit, laneMask((1 << count) - 1)),
                  select(greater(dot(h.n, v), zero), V3{negate(h.n.x), negate(h.n.y), negate(h.n.z)}, h.n),
                  {negate(v.x), negate(v.y), negate(v.z)},
                  material,
                  {gather(materials_.r, material), gather(materials_.g, material), gather(materials_.b, material)},
                  gather(materials_.diffuse, material)};

  // shadeClassic: ambient, each light, then the emission.
  V3 color = mul(s.albedo, gather(materials_.ambient, material));
  for (const Light& light : lights_) {
    color = addLight(materials_, light, shadowSamples_, shapes, s, rngs, color, shadowRays);
  }
  color = add(color, V3{gather(materials_.er, material), gather(materials_.eg, material), gather(materials_.eb, material)});

  // The mirror: R = V + 2 N c1 with c1 = -N.V, leaving from the offset point.
  const F share = mirrors_ ? gather(materials_.reflection, material) : zero;
  const F mirrored = bitAnd(s.live, greater(share, zero));
  V3 r{zero, zero, zero}, ro{zero, zero, zero};
  if (bits(mirrored) != 0) {
    r = add(v, mul(s.n, mul(set1(2.0f), negate(dot(s.n, v)))));
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
