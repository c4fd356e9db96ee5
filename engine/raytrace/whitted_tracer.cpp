#include "raytrace/whitted_tracer.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/brdf.h"
#include "core/spot_cone.h"
#include "raytrace/avx2_region.h"
#include "raytrace/camera.h"
#include "raytrace/camera_lanes.h"
#include "raytrace/ray_cone.h"
#include "raytrace/rng.h"
#include "raytrace/rt_scene.h"
#include "raytrace/tile_render.h"
#include "raytrace/whitted_packets.h"
#include "scene/environment.h"

namespace engine::rt {
namespace {

using detail::PixelStrata;

template <typename T>
struct LightSample {
  glm::vec3 radiance{0.0f};  // colour * intensity (* fall-off)
  Vec3<T> wi{0};             // unit, toward the light (its centre for an area light)
  float visibility = 1.0f;
};

template <typename T>
class Tracer {
 public:
  Tracer(const RtScene& scene, const RenderSettings& settings)
      : scene_(scene), settings_(settings), camera_(scene.camera(), settings.width, settings.height),
        strata_(settings.samplesPerPixel),
        pixelSpread_(pixelConeSpread(scene.camera().fovyDegrees, settings.height, settings.samplesPerPixel)) {
    for (const LightDesc& light : scene.lights()) cones_.push_back(lightCone(light));
  }

  glm::vec3 renderPixel(int x, int y, RayCounters& counters) const {
    Pcg32 rng = Pcg32::forPixel(settings_.seed, x, y);
    const int spp = std::max(1, settings_.samplesPerPixel);
    if (spp == 1) {
      ++counters.primary;
      return Li(primaryRay(x + 0.5, y + 0.5), 0, rng, counters, cameraCone());
    }
    glm::vec3 sum(0.0f);
    for (int j = 0; j < strata_.count().y; ++j) {
      for (int i = 0; i < strata_.count().x; ++i) {
        const glm::dvec2 p = strata_.point(x, y, i, j, rng);
        ++counters.primary;
        sum += Li(primaryRay(p.x, p.y), 0, rng, counters, cameraCone());
      }
    }
    return sum / float(spp);
  }

  // `cone`: the ray's footprint (raytrace/ray_cone.h). `hitDistance`, when given,
  // receives the distance to the surface the ray stops at (left alone when it escapes).
  // A camera sample's ray cone: its share of the pixel's angle (ray_cone.h).
  RayCone cameraCone() const { return RayCone{0.0f, pixelSpread_}; }
  const PixelStrata& strata() const { return strata_; }
  const PinholeCamera& camera() const { return camera_; }

  glm::vec3 Li(const Ray<T>& ray, int depth, Pcg32& rng, RayCounters& counters, RayCone cone = {},
               float* hitDistance = nullptr) const {
    std::optional<SurfaceInteraction<T>> hit = scene_.intersect(ray);
    return LiFrom(ray, hit, depth, rng, counters, cone, hitDistance);
  }

  // Li once `hit`, scene_.intersect(ray), is known (a packet's lane): passed on to the
  // first surface that is there at all, then shaded.
  glm::vec3 LiFrom(const Ray<T>& ray, std::optional<SurfaceInteraction<T>>& hit, int depth, Pcg32& rng,
                   RayCounters& counters, RayCone cone = {}, float* hitDistance = nullptr) const {
    toFirstSolid(ray, hit);
    if (!hit) return escaped(ray.d);
    const Vec3<T> v = glm::normalize(ray.d);
    const float distance = float(hit->t * glm::length(ray.d));
    if (hitDistance) *hitDistance = distance;
    const float footprint = footprintAt(cone, *hit, v, distance);
    // The terrain's layers read the unflipped shading normal, as terrain.frag does.
    const HitMaterial m = scene_.materialAt(hit->material, HitUv(hit->uv, hit->uv1, hit->color), footprint, double(hit->p.y),
                          glm::vec3(hit->ns), hit->dpdu, hit->dpdv);
    if (m.unlit) return depth == 0 ? scene_.fogged(m.albedo, distance) : m.albedo;
    // Surfaces are two-sided: shade with the normal that faces the viewer.
    const Vec3<T> n = glm::dot(hit->n, v) > T(0) ? -hit->ns : hit->ns;
    glm::vec3 color = scene_.render().shading == Shading::Pbr ? shadePbr(*hit, m, n, v, rng, counters)
                                                              : shadeClassic(*hit, m, n, v, rng, counters);
    color += m.emission;
    if (m.reflection > 0.0f && depth < settings_.maxDepth) {
      // The course's mirror: R = V + 2 N c1 with c1 = -N.V.
      const T c1 = -glm::dot(n, v);
      const Vec3<T> r = v + T(2) * c1 * n;
      ++counters.reflection;
      color += m.reflection * Li(hit->spawnRay(r), depth + 1, rng, counters, cone);
    }
    if (m.transmission > 0.0f && depth < settings_.maxDepth && scene_.render().shading == Shading::Pbr)
      color += transmitted(*hit, m, n, v, depth, rng, counters, cone);
    return depth == 0 ? scene_.fogged(color, distance) : color;
  }

 private:
  // KHR_materials_transmission the course's way: one refracted ray (straight on
  // through a thin wall; bent by the ior into and out of a volume, reflected past the
  // critical angle), sharp whatever the roughness, weighed by brdf.glsl's
  // transmittedShare with Fresnel at the view angle, and inside a volume absorbed
  // on its way to the next surface.
  glm::vec3 transmitted(const SurfaceInteraction<T>& hit, const HitMaterial& m, const Vec3<T>& n, const Vec3<T>& v,
                        int depth, Pcg32& rng, RayCounters& counters, RayCone cone) const {
    const float cosV = std::max(float(-glm::dot(n, v)), 1e-4f);
    const glm::vec3 share = brdf::transmittedShare(m.albedo, m.metallic, m.transmission,
                                                   brdf::schlickFresnel90(m.dielectricF0, m.dielectricF90, cosV)) *
                            brdf::sheenScaling(m.sheenColor, m.sheenAlbedo(cosV));
    Vec3<T> d = v;
    if (m.thickness > 0.0f) {
      const T ior = T(std::max(m.ior, 1.0f));
      d = glm::refract(v, n, glm::dot(hit.n, v) < T(0) ? T(1) / ior : ior);
      if (d == Vec3<T>(T(0))) d = v - T(2) * glm::dot(n, v) * n;
    }
    ++counters.reflection;
    float travelled = -1.0f;
    glm::vec3 light = Li(hit.spawnRay(d), depth + 1, rng, counters, cone, &travelled);
    // Inside the volume up to the next surface.
    if (m.thickness > 0.0f && m.attenuationDistance > 0.0f && glm::dot(hit.n, d) < T(0) && travelled >= 0.0f)
      light *= brdf::volumeAttenuation(m.attenuationColor, m.attenuationDistance, travelled);
    return share * light;
  }

  // `hit`, the nearest, made the nearest that is there at all: MASK's cut-away parts
  // and single-sided faces seen from behind are passed, as the rasterizer discards and
  // culls them (at the full-resolution texture level; BLEND is drawn opaque by this
  // tracer). t is along `ray` from its origin. In place: a record returned was read
  // back in 16-byte loads over the intersection's narrower stores of it, a
  // store-forwarding stall on every ray.
  void toFirstSolid(const Ray<T>& ray, std::optional<SurfaceInteraction<T>>& hit) const {
    if (!scene_.hasTransparency() && !scene_.hasSingleSided()) return;
    Ray<T> rest = ray;
    T travelled = T(0);
    for (int pass = 0; hit && pass < 64; ++pass) {
      const bool back = glm::dot(hit->n, rest.d) > T(0);
      if (scene_.surfaceOpacity(hit->material, HitUv(hit->uv, hit->uv1, hit->color), 0.0f, back) > 0.0f) {
        hit->t += travelled;
        return;
      }
      travelled += hit->t;
      rest = Ray<T>{hit->spawnRay(rest.d).o, rest.d, rest.tMax - hit->t};
      hit = scene_.intersect(rest);
    }
    hit.reset();
  }

  // The camera's ray through the image point, ending at the far plane as the
  // rasterizer's view does: past it both show the sky.
  Ray<T> primaryRay(double px, double py) const {
    return camera_.clippedToFarPlane(camera_.generateRay<T>(px, py));
  }

  // The course's model (core/brdf.h's classicReflected, as the rasterizer's shadeLight)
  // per light, plus colour * ambient; the mirror term is added by Li.
  glm::vec3 shadeClassic(const SurfaceInteraction<T>& si, const HitMaterial& m, const Vec3<T>& n, const Vec3<T>& v,
                         Pcg32& rng, RayCounters& counters) const {
    glm::vec3 color = m.albedo * m.ambient;
    for (std::size_t i = 0; i < scene_.lights().size(); ++i) {
      const LightSample<T> ls = sampleLight(si, scene_.lights()[i], cones_[i], rng, counters);
      if (ls.visibility <= 0.0f) continue;
      color += ls.radiance * ls.visibility *
               brdf::classicReflected(glm::vec3(n), -glm::vec3(v), glm::vec3(ls.wi), m.albedo, m.diffuse, m.specular,
                                      m.shininess);
    }
    return color;
  }

  // glTF's metallic-roughness BRDF (core/brdf.h, the rasterizer's own) per light, and
  // the rasterizer's hemisphere ambient scaled by the material.
  glm::vec3 shadePbr(const SurfaceInteraction<T>& si, const HitMaterial& m, const Vec3<T>& n, const Vec3<T>& v,
                     Pcg32& rng, RayCounters& counters) const {
    const glm::vec3 nf(n);
    const glm::vec3 toEye = -glm::vec3(v);
    const float nDotV = glm::max(glm::dot(nf, toEye), 1e-4f);
    const ViewLayers view = m.atView(nf, nDotV);
    glm::vec3 color(0.0f);
    for (std::size_t i = 0; i < scene_.lights().size(); ++i) {
      const LightSample<T> ls = sampleLight(si, scene_.lights()[i], cones_[i], rng, counters);
      const glm::vec3 l(ls.wi);
      const float nDotL = glm::dot(nf, l);
      if (nDotL <= 0.0f || ls.visibility <= 0.0f) continue;
      const glm::vec3 f =
          brdf::layeredBrdf(nf, toEye, l, m.albedo, m.metallic, m.roughness, m.dielectricF0, m.dielectricF90, nf,
                            m.clearcoat, m.clearcoatRoughness, m.transmission, m.sheenColor, m.sheenRoughness,
                            view.sheenScale, view.anisotropyT, view.anisotropyB, view.anisotropy, view.iridescenceF,
                            m.iridescence);
      color += ls.radiance * ls.visibility * brdf::brdfLightFactor(f, nDotL);
    }
    // The same hemisphere ambient as the rasterizer's shadeAmbient.
    const glm::vec3 ambientLight = glm::mix(scene_.ambientGround(), scene_.ambientSky(), 0.5f + 0.5f * nf.y);
    return color + ambientLight * brdf::hemisphereAmbient(m.albedo, m.metallic, m.roughness, m.dielectricF0, nDotV,
                                                          m.clearcoat, m.clearcoatRoughness, m.transmission,
                                                          m.sheenColor, view.sheenAlbedo, view.iridescenceF,
                                                          m.iridescence);
  }

  LightSample<T> sampleLight(const SurfaceInteraction<T>& si, const LightDesc& light, const LightCone& cone, Pcg32& rng,
                             RayCounters& counters) const {
    LightSample<T> ls;
    ls.radiance = light.color * light.intensity;
    switch (light.type) {
      case LightType::Sun: {
        ls.wi = glm::normalize(Vec3<T>(light.direction));
        if (light.shadows) ls.visibility = scene_.transmittance<T>(si.spawnRay(ls.wi), nullptr, counters.shadow);
        break;
      }
      case LightType::Point:
      case LightType::Spot: {
        const Vec3<T> target(light.position);
        const Vec3<T> toLight = target - si.p;
        const T dist2 = glm::dot(toLight, toLight);
        ls.wi = toLight / std::sqrt(dist2);
        if (light.falloff) ls.radiance /= float(dist2);
        if (light.type == LightType::Spot) {
          const float share =
              spottext::spotAttenuation(glm::dot(glm::vec3(ls.wi), cone.axisToLight), cone.cosOuter, cone.cosInner);
          ls.radiance *= share;
          if (share == 0.0f) break;  // outside the cone: no shadow ray
        }
        // The light is a point, not geometry: stop at it (tMax 1 on d = target - o).
        if (light.shadows) ls.visibility = scene_.transmittance(si.spawnRayTo(target, T(1)), &target, counters.shadow);
        break;
      }
      case LightType::Area: {
        const Vec3<T> center(light.position);
        ls.wi = glm::normalize(center - si.p);
        if (light.shadows) ls.visibility = areaVisibility(si, light, rng, counters);
        break;
      }
    }
    return ls;
  }

  // The share of N x N stratified, jittered points on the rectangle that the point sees.
  float areaVisibility(const SurfaceInteraction<T>& si, const LightDesc& light, Pcg32& rng,
                       RayCounters& counters) const {
    const int n = std::max(1, settings_.shadowSamples);
    const Vec3<T> center(light.position), edgeU(light.edgeU), edgeV(light.edgeV);
    float visible = 0.0f;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const T u = (T(i) + T(rng.uniform())) / T(n) - T(0.5);
        const T w = (T(j) + T(rng.uniform())) / T(n) - T(0.5);
        const Vec3<T> target = center + u * edgeU + w * edgeV;
        visible += scene_.transmittance(si.spawnRayTo(target, T(1)), &target, counters.shadow);
      }
    }
    return visible / float(n * n);
  }

  // What the scene's environment sends along the escaping ray: its sky's gradient,
  // background colour or image (raytrace/environment.h).
  glm::vec3 escaped(const Vec3<T>& dir) const { return scene_.environment().radiance(glm::vec3(dir)); }

  const RtScene& scene_;
  const RenderSettings& settings_;
  PinholeCamera camera_;
  PixelStrata strata_;
  float pixelSpread_ = 0.0f;
  std::vector<LightCone> cones_;  // each light's, made once (scene/environment.h)
};

// Up to eight pixels of a row side by side, a lane each, their samples in step and in
// renderPixel's order for each pixel: per stratum, each lane's image point drawn from
// its own pixel's stream, then `trace(px, py, rngs)` (the lanes' first hits, which
// may draw from the streams too) and `colour(p, rngs[p])` each lane's sample, the
// samples summed from zero and averaged as renderPixel does. Lanes past `pixels`
// repeat the first point and are not coloured.
constexpr int kRowLanes = 8;

template <typename Trace, typename Colour>
void sampleLanes(const PixelStrata& strata, const RenderSettings& settings, int x, int pixels, int y,
                 glm::vec3* out, RayCounters& counters, Trace&& trace, Colour&& colour) {
  const int spp = std::max(1, settings.samplesPerPixel);
  Pcg32 rngs[kRowLanes];
  for (int p = 0; p < pixels; ++p) rngs[p] = Pcg32::forPixel(settings.seed, x + p, y);
  double px[kRowLanes], py[kRowLanes];
  for (int p = 0; p < pixels; ++p) out[p] = glm::vec3(0.0f);
  for (int j = 0; j < strata.count().y; ++j) {
    for (int i = 0; i < strata.count().x; ++i) {
      for (int p = 0; p < kRowLanes; ++p) {
        const glm::dvec2 q = p >= pixels ? glm::dvec2(px[0], py[0])
                             : spp == 1  ? glm::dvec2(x + p + 0.5, y + 0.5)
                                         : strata.point(x + p, y, i, j, rngs[p]);
        px[p] = q.x, py[p] = q.y;
      }
      counters.primary += std::uint64_t(pixels);
      trace(px, py, rngs);
      for (int p = 0; p < pixels; ++p) {
        const glm::vec3 c = colour(p, rngs[p]);
        // One sample is the pixel's colour as it is; more are summed from zero.
        out[p] = spp == 1 ? c : out[p] + c;
      }
    }
  }
  if (spp > 1) {
    for (int p = 0; p < pixels; ++p) out[p] = out[p] / float(spp);
  }
}

// The Whitted tracer's image with the first hits eight samples at a time
// (whitted_packets.h): the pixels' sample positions drawn as renderPixel draws them,
// the mirrors' rays finished by the scalar Li, the sums and means taken as there, so
// each pixel is renderPixel's bit for bit.
class PacketTracer {
 public:
  PacketTracer(const Tracer<float>& scalar, const WhittedPackets& packets, const RtScene& scene,
               const RenderSettings& settings)
      : scalar_(scalar), packets_(packets), scene_(scene), settings_(settings) {}

  // Eight pixels at a time, a lane each, their samples in step: each lane's positions
  // and area-light points drawn from its pixel's stream in renderPixel's order, the
  // samples summed in their order and averaged.
  void renderSpan(int x0, int x1, int y, glm::vec3* out, RayCounters& counters) const {
    for (int x = x0; x < x1; x += kLanes) renderLanes(x, std::min(kLanes, x1 - x), y, out + (x - x0), counters);
  }

 private:
  static constexpr int kLanes = WhittedPackets::kLanes;
  static_assert(kLanes == kRowLanes);

  void renderLanes(int x, int pixels, int y, glm::vec3* out, RayCounters& counters) const {
    WhittedPackets::Lanes lanes;
    sampleLanes(
        scalar_.strata(), settings_, x, pixels, y, out, counters,
        [&](const double* px, const double* py, Pcg32* rngs) { packets_.trace(px, py, pixels, rngs, lanes, counters.shadow); },
        [&](int p, Pcg32& rng) { return finish(lanes, p, rng, counters); });
  }

  // Tracer::Li past the first hit: the environment where the sample escaped, else the
  // mirror's ray traced on (its cone widened to the hit, as footprintAt leaves it) and
  // the fog.
  glm::vec3 finish(const WhittedPackets::Lanes& lanes, int i, Pcg32& rng, RayCounters& counters) const {
    if ((lanes.hits >> i & 1) == 0) return scene_.environment().radiance(lanes.direction(i));
    glm::vec3 color = lanes.color(i);
    if (lanes.reflection[i] > 0.0f) {
      RayCone cone = scalar_.cameraCone();
      cone.width += cone.spread * lanes.distance[i];
      ++counters.reflection;
      color += lanes.reflection[i] * scalar_.Li(lanes.reflected(i), 1, rng, counters, cone);
    }
    return scene_.fogged(color, lanes.distance[i]);
  }

  const Tracer<float>& scalar_;
  const WhittedPackets& packets_;
  const RtScene& scene_;
  const RenderSettings& settings_;
};

// The scalar Whitted tracer a row at a time, for scenes the packets do not take
// (triangles, textures, PBR): each sample's camera rays made for eight pixels at once
// (camera_lanes.h, the same rays bit for bit), their first hits found together
// (RtScene::intersectCoherent: each group's BVH walked once for the eight), then
// shaded and traced on one by one by Tracer::LiFrom. Each pixel's stream is drawn in
// renderPixel's order (a sample's position, then its light samples), its samples
// summed and averaged as there: renderPixel's bits, but where the packet's hit is not
// the lone ray's (RtScene::intersectCoherent: two triangles at exactly the same
// distance, or one an ulp before a hit that the lone ray's box test rounded away).
class SpanTracer {
 public:
  SpanTracer(const Tracer<float>& scalar, const RtScene& scene, const RenderSettings& settings)
      : scalar_(scalar), scene_(scene), settings_(settings) {}

  void renderSpan(int x0, int x1, int y, glm::vec3* out, RayCounters& counters) const {
    for (int x = x0; x < x1; x += kLanes) {
      renderLanes(x, std::min(kLanes, x1 - x), y, out + (x - x0), counters);
    }
  }

 private:
  static constexpr int kLanes = kRowLanes;  // lanes8::cameraRays' rays at a time

  void renderLanes(int x, int pixels, int y, glm::vec3* out, RayCounters& counters) const {
    alignas(32) float dx[kLanes], dy[kLanes], dz[kLanes], tMax[kLanes];
    const Vec3<float> origin(scalar_.camera().position());
    Ray<float> rays[kLanes];
    std::optional<SurfaceInteraction<float>> hits[kLanes];
    sampleLanes(
        scalar_.strata(), settings_, x, pixels, y, out, counters,
        [&](const double* px, const double* py, Pcg32*) {
          lanes8::cameraRays(scalar_.camera(), px, py, dx, dy, dz, tMax);
          for (int p = 0; p < kLanes; ++p) rays[p] = Ray<float>{origin, Vec3<float>(dx[p], dy[p], dz[p]), tMax[p]};
          scene_.intersectCoherent(rays, hits);
        },
        [&](int p, Pcg32& rng) { return scalar_.LiFrom(rays[p], hits[p], 0, rng, counters, scalar_.cameraCone()); });
  }

  const Tracer<float>& scalar_;
  const RtScene& scene_;
  const RenderSettings& settings_;
};

}  // namespace

WhittedIntegrator::WhittedIntegrator(const RtScene& scene, RenderSettings settings)
    : IntegratorMethod(scene, std::move(settings)) {
  if (std::optional<WhittedPackets> packets = WhittedPackets::create(scene, this->settings())) {
    packets_ = std::make_shared<const WhittedPackets>(std::move(*packets));
  }
}

RenderResult WhittedIntegrator::render() const {
  const RenderSettings& s = settings();
  if (s.precision == Precision::Double) return detail::renderTiles(Tracer<double>(scene(), s), s);
  const Tracer<float> tracer(scene(), s);
  if (packets_) return detail::renderTiles(PacketTracer(tracer, *packets_, scene(), s), s);
  if (firstHitsInRows(s)) return detail::renderTiles(SpanTracer(tracer, scene(), s), s);
  return detail::renderTiles(tracer, s);
}

glm::vec3 WhittedIntegrator::renderPixel(int x, int y, RayCounters& counters) const {
  if (settings().precision == Precision::Double) return Tracer<double>(scene(), settings()).renderPixel(x, y, counters);
  return Tracer<float>(scene(), settings()).renderPixel(x, y, counters);
}

bool WhittedIntegrator::firstHitsInRows(const RenderSettings& settings) {
  return settings.method == Method::Whitted && settings.precision == Precision::Float && cpuHasAvx2();
}

glm::vec3 WhittedIntegrator::renderPixelSamples(int x, int y, int, int, RayCounters& counters) const {
  return renderPixel(x, y, counters);
}

void WhittedIntegrator::renderSpanSamples(int x0, int x1, int y, int, int, glm::vec3* out,
                                          RayCounters& counters) const {
  if (packets_) {
    const Tracer<float> tracer(scene(), settings());
    PacketTracer(tracer, *packets_, scene(), settings()).renderSpan(x0, x1, y, out, counters);
  } else if (firstHitsInRows(settings())) {
    const Tracer<float> tracer(scene(), settings());
    SpanTracer(tracer, scene(), settings()).renderSpan(x0, x1, y, out, counters);
  } else {
    for (int x = x0; x < x1; ++x) out[x - x0] = renderPixel(x, y, counters);
  }
}

glm::vec3 WhittedIntegrator::traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) const {
  Pcg32 rng(mixBits(seed), 1);
  if (settings().precision == Precision::Double) return Tracer<double>(scene(), settings()).Li(ray, 0, rng, counters);
  const Ray<float> r{Vec3<float>(ray.o), Vec3<float>(ray.d), float(ray.tMax)};
  return Tracer<float>(scene(), settings()).Li(r, 0, rng, counters);
}

}  // namespace engine::rt
