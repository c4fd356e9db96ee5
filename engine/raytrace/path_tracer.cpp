#include "raytrace/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "core/phase.h"
#include "raytrace/bsdf.h"
#include "raytrace/camera.h"
#include "raytrace/camera_lanes.h"
#include "raytrace/media.h"
#include "raytrace/light_sample.h"
#include "raytrace/path_lights.h"
#include "raytrace/ray_cone.h"
#include "raytrace/rng.h"
#include "raytrace/rt_scene.h"
#include "raytrace/sampling.h"
#include "raytrace/tile_render.h"

namespace engine::rt {
namespace {

float maxComponent(const glm::vec3& c) { return std::max({c.x, c.y, c.z}); }

// Cut-away and transparent surfaces a ray may pass before it gives up: a forest of
// alpha-tested leaves is deep, but not this deep.
constexpr int kMaxPassThrough = 64;

// kMedium: the scene has media (raytrace/media.h). A tracer of its own, so that
// scenes without one run the code they ran before media, not its tests: with them
// the room took 4 % longer.
template <typename T, bool kMedium>
class PathTracer {
 public:
  static constexpr bool kDouble = std::is_same_v<T, double>;
  PathTracer(const RtScene& scene, const PathLights& lights, const RenderSettings& settings)
      : scene_(scene), env_(lights.environment), lights_(lights.lights), coneSun_(lights.coneSun), settings_(settings),
        camera_(scene.camera(), settings.width, settings.height), cameraPosition_(scene.camera().position),
        media_(Media::of(scene.fog(), scene.atmosphere(), scene.media())),
        space_(media_ && media_->hasPlanet()),
        pixelSpread_(pixelConeSpread(scene.camera().fovyDegrees, settings.height,
                                     settings.totalSamples > 0 ? settings.totalSamples : settings.samplesPerPixel)) {}

  // The mean of samples [firstSample, firstSample + spp) of the pixel. Their image
  // positions follow the R2 sequence (Roberts 2018: the plastic number's powers, a
  // low-discrepancy sequence whose every prefix is well spread, so no strata need
  // the total in advance), turned by a random offset per pixel; each sample has a
  // random stream of its own.
  glm::vec3 renderPixel(int x, int y, RayCounters& counters) const {
    glm::vec3 c;
    renderSpan(x, x + 1, y, &c, counters);
    return c;
  }

  // renderPixel of pixels x0..x1-1 of row y into out[0..]: their paths traced side by
  // side, a bounce at a time, so that the spheres and planes meet four rays at once
  // (RtScene::intersectMany). Each path is the one Li traces alone, bit for bit: it
  // draws from its own stream in the same order.
  void renderSpan(int x0, int x1, int y, glm::vec3* out, RayCounters& counters) const {
    const int first = std::max(0, settings_.firstSample), spp = std::max(1, settings_.samplesPerPixel);
    std::vector<Path>& paths = batch_.paths;
    paths.clear();
    batch_.px.clear(), batch_.py.clear();
    for (int x = x0; x < x1; ++x) {
      Pcg32 pixelRng = Pcg32::forPixel(settings_.seed, x, y);
      const double offsetX = double(pixelRng.uniform()), offsetY = double(pixelRng.uniform());
      for (int s = first; s < first + spp; ++s) {
        constexpr double kR2x = 0.75487766624669276, kR2y = 0.56984029099805327;  // 1/g, 1/g^2, g^3 = g + 1
        const double jx = offsetX + kR2x * double(s), jy = offsetY + kR2y * double(s);
        ++counters.primary;
        batch_.px.push_back(x + (jx - std::floor(jx)));
        batch_.py.push_back(y + (jy - std::floor(jy)));
        paths.push_back(Path(Ray<T>{}, Pcg32::forSample(settings_.seed, x, y, s), RayCone{0.0f, pixelSpread_}));
      }
    }
    cameraRays(paths);
    // A few dozen paths at a time: enough for whole quads of rays, few enough that
    // their hits stay in the cache however many samples a pixel takes.
    constexpr std::size_t kBatch = 64;
    for (std::size_t i = 0; i < paths.size(); i += kBatch)
      traceAll(paths.data() + i, std::min(kBatch, paths.size() - i), counters);
    for (int x = x0; x < x1; ++x) {
      glm::vec3 sum(0.0f);
      for (int s = 0; s < spp; ++s) {
        const Path& p = paths[std::size_t(x - x0) * std::size_t(spp) + std::size_t(s)];
        sum += finite(p.firstHit < 0.0f || kMedium ? p.radiance : scene_.fogged(p.radiance, p.firstHit));
      }
      out[x - x0] = sum / float(spp);
    }
  }

  glm::vec3 Li(Ray<T> ray, Pcg32& rng, RayCounters& counters, RayCone cone = {}) const {
    Path path(ray, rng, cone);
    while (bounce(path, scene_.intersect(path.ray), counters)) {
    }
    rng = path.rng;
    return path.radiance;
  }

 private:
  // One path's state between bounces.
  struct Path {
    Path(const Ray<T>& r, const Pcg32& stream, RayCone c) : ray(r), rng(stream), cone(c) {}
    Ray<T> ray;
    Pcg32 rng;
    RayCone cone;
    glm::vec3 radiance{0.0f}, beta{1.0f};
    glm::vec3 absorption{0.0f};  // of the volume the ray travels in (KHR_materials_volume)
    bool countEmitters = true;   // a camera ray or a mirror: nothing sampled the light
    float bsdfPdf = 0.0f;        // of the direction `ray` was drawn with
    int passes = 0;              // through cut-away or transparent surfaces
    int depth = 0;
    float firstHit = -1.0f;  // the distance to the first surface the path scatters at; -1 none
    int scatterings = 0;     // in media
  };
  // A span's paths and their nearest hits, kept between calls so that no bounce
  // allocates.
  struct Batch {
    std::vector<Path> paths;
    std::vector<double> px, py;  // the paths' image points
    std::vector<float> dx, dy, dz, tMax;  // their camera rays, eight at a time
    std::vector<std::size_t> live;
    std::vector<const Ray<T>*> rays;
    std::vector<std::optional<SurfaceInteraction<T>>> hits;
  };

  // The camera's ray through each path's image point (batch_.px, py): eight at a
  // time where the CPU has AVX2 (camera_lanes.h, the same rays bit for bit).
  void cameraRays(std::vector<Path>& paths) const {
    if (std::is_same_v<T, float> && cpuHasAvx2()) {
      const std::size_t n = paths.size();
      batch_.dx.resize(n), batch_.dy.resize(n), batch_.dz.resize(n), batch_.tMax.resize(n);
      lanes8::cameraRays(camera_, batch_.px.data(), batch_.py.data(), n, batch_.dx.data(), batch_.dy.data(),
                         batch_.dz.data(), batch_.tMax.data());
      const Vec3<T> origin(camera_.position());
      for (std::size_t i = 0; i < n; ++i) {
        paths[i].ray.o = origin;
        paths[i].ray.d = Vec3<T>(batch_.dx[i], batch_.dy[i], batch_.dz[i]);
        paths[i].ray.tMax = T(batch_.tMax[i]);
      }
      return;
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const Ray<T> ray = camera_.clippedToFarPlane(camera_.generateRay<T>(batch_.px[i], batch_.py[i]));
      paths[i].ray.o = ray.o;
      paths[i].ray.d = ray.d;
      paths[i].ray.tMax = ray.tMax;
    }
  }

  // Every path to its end, all of them a bounce at a time: the nearest hits of all
  // the paths still going, then each one's bounce. (Their shadow rays are traced one
  // at a time, inside the bounce: gathered for the whole batch as well, they were
  // slower, 0.96x, for the light samples kept aside meanwhile.)
  void traceAll(Path* paths, std::size_t count, RayCounters& counters) const {
    std::vector<std::size_t>& live = batch_.live;
    live.resize(count);
    for (std::size_t i = 0; i < count; ++i) live[i] = i;
    while (!live.empty()) {
      batch_.rays.resize(live.size());
      batch_.hits.resize(live.size());
      for (std::size_t i = 0; i < live.size(); ++i) batch_.rays[i] = &paths[live[i]].ray;
      intersectAll(batch_.rays.data(), live.size(), batch_.hits.data());
      std::size_t kept = 0;
      for (std::size_t i = 0; i < live.size(); ++i) {
        if (bounce(paths[live[i]], batch_.hits[i], counters)) live[kept++] = live[i];
      }
      live.resize(kept);
    }
  }

  void intersectAll(const Ray<T>* const* rays, std::size_t count, std::optional<SurfaceInteraction<T>>* hits) const {
    if constexpr (std::is_same_v<T, float>) {
      scene_.intersectMany(rays, count, hits);
    } else {
      for (std::size_t i = 0; i < count; ++i) hits[i] = scene_.intersect(*rays[i]);
    }
  }

  // One vertex of the path: what the ray found at `hit`, and the next ray. False when
  // the path ends.
  bool bounce(Path& path, const std::optional<SurfaceInteraction<T>>& hit, RayCounters& counters) const {
    Ray<T>& ray = path.ray;
    Pcg32& rng = path.rng;
    glm::vec3& beta = path.beta;
    const Vec3<T> v = glm::normalize(ray.d);
    const glm::vec3 d(v);
    const T tHit = hit ? hit->t : ray.tMax;
    if (path.absorption != glm::vec3(0.0f))
      beta *= glm::exp(-path.absorption * float(double(tHit) * glm::length(glm::dvec3(ray.d))));
    if constexpr (kMedium) {
      if (!media_->homogeneous()) return bounceInMedia(path, hit, v, counters);
    }
    // In a homogeneous fog the ray may scatter before it gets there (medium.h).
    Medium::Flight flight;
    if constexpr (kMedium) flight = media_->homogeneous()->fly(double(tHit) * glm::length(glm::dvec3(ray.d)), rng.uniform(), rng.uniform());
    const T tEnd = flight.scattered ? T(flight.distance / glm::length(glm::dvec3(ray.d))) : tHit;
    path.radiance += beta * emittersAlong(ray, d, tEnd, !hit && !flight.scattered, path, flight.weight);
    if constexpr (kMedium) {
      beta *= flight.weight;
      if (flight.scattered) return scatter(path, ray(tEnd), d, Phase{media_->homogeneous()->anisotropy, false}, counters);
    }
    if (!hit) return false;
    return surface(path, *hit, v, counters);
  }

  // The surface the path's ray found: cut away, passed through, or shaded.
  [[gnu::always_inline]] bool surface(Path& path, const SurfaceInteraction<T>& hit, const Vec3<T>& v, RayCounters& counters) const {
    Ray<T>& ray = path.ray;
    Pcg32& rng = path.rng;
    const float footprint = footprintAt(path.cone, hit, v, float(hit.t * glm::length(ray.d)));
    // MASK's cut-away parts and single-sided faces seen from behind are not there;
    // BLEND stops a share alpha of the paths (stochastic transparency). Either way
    // the ray goes on unbent, no bounce.
    if (const float opacity =
            scene_.surfaceOpacity(hit.material, HitUv(hit.uv, hit.uv1, hit.color), footprint, glm::dot(hit.n, v) > T(0));
        opacity < 1.0f && (opacity <= 0.0f || rng.uniform() >= opacity)) {
      if (++path.passes > kMaxPassThrough) return false;
      ray = Ray<T>{hit.spawnRay(ray.d).o, ray.d, ray.tMax - hit.t};
      return true;
    }
    const HitMaterial m =
        scene_.materialAt(hit.material, HitUv(hit.uv, hit.uv1, hit.color), footprint, double(hit.p.y),
                          glm::vec3(hit.ns), hit.dpdu, hit.dpdv);
    if (path.firstHit < 0.0f) path.firstHit = float(glm::length(glm::dvec3(hit.p) - cameraPosition_));
    const bool pbr = scene_.render().shading == Shading::Pbr;
    return shade(path, hit, m, pbr, v, counters);
  }

  // A vertex on a surface of material m: what it emits, its light, its bounce.
  [[gnu::always_inline]] bool shade(Path& path, const SurfaceInteraction<T>& hit, const HitMaterial& m, bool pbr, const Vec3<T>& v,
             RayCounters& counters) const {
    Pcg32& rng = path.rng;
    glm::vec3& beta = path.beta;
    const glm::vec3 d(v);
    path.radiance += beta * m.emission;
    if (m.unlit) {
      path.radiance += beta * m.albedo;  // KHR_materials_unlit: its colour, and no bounce
      return false;
    }
    // Past the last bounce a vertex only shows what it emits: the BSDF ray that
    // found it still had to be traced, for the lights MIS shares with it.
    if (path.depth > settings_.maxDepth) return false;
    // Two-sided surfaces: both normals turned to the side the ray came from.
    const bool back = glm::dot(hit.n, v) > T(0);
    const glm::vec3 ng = glm::vec3(back ? -hit.n : hit.n);
    const glm::vec3 ns = glm::vec3(back ? -hit.ns : hit.ns);
    const glm::vec3 wo = -d;
    const Bsdf bsdf = pbr ? Bsdf::metallicRoughness(m, ns, wo, !back) : Bsdf::classic(m, ns, wo);
    if (bsdf.hasDiffuseOrGlossy()) path.radiance += beta * directLight(hit, bsdf, ng, rng, counters);
    const glm::vec2 u = rng.uniform2();
    const BsdfSample s = bsdf.sample(u, rng.uniform());
    // A direction under the geometric surface would leak light through it; one
    // transmitted must be under it.
    if (!s.drawn || (glm::dot(s.wi, ng) <= 0.0f) != s.transmitted) return false;
    // In or out of a volume: its absorption applies along the next segment.
    if (m.transmission > 0.0f && m.thickness > 0.0f)
      path.absorption = glm::dot(glm::dvec3(s.wi), glm::dvec3(hit.n)) < 0.0 ? volumeAbsorption(m) : glm::vec3(0.0f);
    beta *= s.weight;
    path.countEmitters = s.delta;
    path.bsdfPdf = s.pdf;
    return continuePath(path, hit.spawnRay(Vec3<T>(s.wi)), counters);
  }

  // Russian roulette past its depth, then the next ray: false when the path ends.
  bool continuePath(Path& path, const Ray<T>& next, RayCounters& counters) const {
    if (path.depth + 1 >= settings_.rouletteDepth) {
      const float survive = std::min(1.0f, maxComponent(path.beta));
      if (!(survive > 0.0f) || path.rng.uniform() >= survive) return false;
      path.beta /= survive;
    }
    ++counters.reflection;
    ++path.depth;
    // Member by member: the whole struct assigned was stored in narrow pieces and
    // read back in 16-byte loads, a store-forwarding stall on every bounce.
    path.ray.o = next.o;
    path.ray.d = next.d;
    path.ray.tMax = next.tMax;
    return true;
  }

  // Beer-Lambert's coefficient per unit length: attenuationColor remains of white
  // light after attenuationDistance (core/brdf.h's volumeAttenuation).
  static glm::vec3 volumeAbsorption(const HitMaterial& m) {
    if (m.attenuationDistance <= 0.0f) return glm::vec3(0.0f);
    return -glm::log(glm::max(m.attenuationColor, glm::vec3(1e-6f))) / m.attenuationDistance;
  }

  static glm::vec3 finite(const glm::vec3& c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) ? c : glm::vec3(0.0f);
  }

  // What the ray meets on its way to tHit that no surface is: the area lights it
  // passes through, and, when it escapes, the environment and a cone sun. Weighed
  // against the light samples that could have found them, unless nothing sampled
  // them (countEmitters: camera rays and mirrors). In a medium, `escapeWeight` is
  // what the flight that got past them weighs (medium.h); an area light at s
  // weighs what reaching s does.
  glm::vec3 emittersAlong(const Ray<T>& ray, const glm::vec3& d, T tHit, bool escaped, const Path& path,
                          const glm::vec3& escapeWeight) const {
    const bool countEmitters = path.countEmitters;
    const float bsdfPdf = path.bsdfPdf;
    glm::vec3 sum(0.0f);
    for (const PathLight& l : lights_) {
      if (l.type != LightType::Area) continue;
      float lightPdf = 0.0f;
      double distance = 0.0;
      if (!hitsArea(l, ray, d, tHit, &lightPdf, &distance)) continue;
      const glm::vec3 light = l.power * (countEmitters ? 1.0f : powerHeuristic(bsdfPdf, lightPdf));
      if constexpr (kMedium) {
        sum += light * reachedWeight(ray, distance);
      } else {
        sum += light;
      }
    }
    if (!escaped) return sum;
    // What arrives from beyond, times what the medium's flight let through (1 without).
    for (const PathLight& l : lights_) {
      if (l.type != LightType::Sun || l.cosMax >= 1.0f || glm::dot(d, l.direction) < l.cosMax) continue;
      sum += l.radiance * (countEmitters ? 1.0f : powerHeuristic(bsdfPdf, uniformConePdf(l.cosMax))) * escapeWeight;
    }
    // Beyond a planet's air is black space: its sun is a light.
    if (space_) return sum;
    // The camera sees the sky's sun disk as the rasterizer draws it; light paths find
    // the sun through its light alone.
    if (path.depth == 0) return sum + scene_.environment().radiance(d, !coneSun_) * escapeWeight;
    if (env_.black()) return sum;
    return sum + env_.radiance(d) * (countEmitters ? 1.0f : powerHeuristic(bsdfPdf, env_.pdf(d))) * escapeWeight;
  }

  // What a flight that got `distance` metres along the ray weighs: the transmittance
  // over the chance of getting there (the distance was drawn by one channel's
  // optical depth, weighed over the three).
  glm::vec3 reachedWeight(const Ray<T>& ray, double distance) const {
    const glm::vec3 tr = media_->transmittance(glm::dvec3(ray.o), glm::normalize(glm::dvec3(ray.d)), distance);
    const float mean = (tr.x + tr.y + tr.z) / 3.0f;
    return mean > 0.0f ? tr / mean : glm::vec3(0.0f);
  }

  // Next-event estimation: one sample of every light and of the environment, each
  // with its shadow ray, weighed by MIS against the BSDF sample that could find it.
  glm::vec3 directLight(const SurfaceInteraction<T>& si, const Bsdf& bsdf, const glm::vec3& ng, Pcg32& rng,
                        RayCounters& counters) const {
    return sampleEveryLight(si, rng, [&](const LightSample<T>& ls, bool shadows) __attribute__((always_inline)) {
      return kMedium ? shadeThroughMedium(si, ls, shadows, bsdf, ng, counters)
                     : shadeLight(si, ls, shadows, bsdf, ng, counters);
    });
  }

  // One sample of every light and of the environment from `at`, in that order from
  // `rng`, each given to shadeSample(sample, its light casts shadows); their sum. A
  // surface's and a medium's next-event estimation both.
  template <typename ShadeSample>
  glm::vec3 sampleEveryLight(const SurfaceInteraction<T>& at, Pcg32& rng, ShadeSample&& shadeSample) const {
    glm::vec3 sum(0.0f);
    for (const PathLight& l : lights_) {
      const glm::vec2 u = rng.uniform2();
      LightSample<T> ls;
      if (sampleLight(at, l, u, ls)) sum += shadeSample(ls, l.shadows);
    }
    // Beyond a planet's air is black space, whatever the sky says.
    if (!env_.black() && !space_) {
      const glm::vec2 u = rng.uniform2();
      LightSample<T> ls;
      ls.wi = env_.sample(u, &ls.pdf);
      if (ls.pdf > 0.0f) {
        ls.value = env_.radiance(ls.wi) / ls.pdf;
        sum += shadeSample(ls, true);
      }
    }
    return sum;
  }

  // Inlined, as it always was before shadeThroughMedium called it too (3 % of the
  // room's time went to the call).
  [[gnu::always_inline]] glm::vec3 shadeLight(const SurfaceInteraction<T>& si, const LightSample<T>& ls, bool shadows,
                                         const Bsdf& bsdf, const glm::vec3& ng, RayCounters& counters) const {
    if (glm::dot(ls.wi, ng) <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 f = bsdf.f(ls.wi);
    if (f == glm::vec3(0.0f) || ls.value == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const float visible = shadows ? transmittance(si, ls, counters) : 1.0f;
    if (visible <= 0.0f) return glm::vec3(0.0f);
    const float cosine = std::max(glm::dot(bsdf.normal(), ls.wi), 0.0f);
    const float weight = ls.pdf > 0.0f ? powerHeuristic(ls.pdf, bsdf.pdf(ls.wi)) : 1.0f;
    return f * ls.value * (cosine * weight * visible);
  }

  // shade() in a medium: what it lets through to the light (no shadow ray where
  // that is nothing). Kept apart and out of line: shade grown by it was no longer
  // inlined, which slowed scenes without a medium by 3 %.
  [[gnu::noinline]] glm::vec3 shadeThroughMedium(const SurfaceInteraction<T>& si, const LightSample<T>& ls,
                                                 bool shadows, const Bsdf& bsdf, const glm::vec3& ng,
                                                 RayCounters& counters) const {
    const glm::vec3 lit = shadeLight(si, ls, shadows, bsdf, ng, counters);
    if (lit == glm::vec3(0.0f)) return lit;
    return lit * mediumAlong(si.p, ls);
  }

  // What the media let through from `from` to the light sample's end (all of it
  // without media; to a direction, what is left at infinity).
  glm::vec3 mediumAlong(const Vec3<T>& from, const LightSample<T>& ls) const {
    if constexpr (!kMedium) return glm::vec3(1.0f);
    const double distance = ls.toPoint ? glm::length(glm::dvec3(ls.target) - glm::dvec3(from))
                                       : std::numeric_limits<double>::infinity();
    const glm::dvec3 dir = ls.toPoint ? (glm::dvec3(ls.target) - glm::dvec3(from)) / distance : glm::dvec3(ls.wi);
    return media_->transmittance(glm::dvec3(from), dir, distance);
  }

  // bounce() in media other than a homogeneous fog alone (media.h): where the ray
  // scatters before the surface, if it does, or the planet's ground where a ray that
  // met no surface comes down.
  [[gnu::noinline]] bool bounceInMedia(Path& path, const std::optional<SurfaceInteraction<T>>& hit, const Vec3<T>& v,
                                       RayCounters& counters) const {
    const Ray<T>& ray = path.ray;
    const glm::vec3 d(v);
    const double length = glm::length(glm::dvec3(ray.d));
    // Without a surface the ray goes on through the air, to space or the ground.
    const double maxDistance =
        hit ? double(hit->t) * length : (space_ ? std::numeric_limits<double>::infinity() : double(ray.tMax) * length);
    const float uChannel = path.rng.uniform(), u = path.rng.uniform();
    const Media::Flight f = media_->fly(glm::dvec3(ray.o), glm::dvec3(v), maxDistance, uChannel, u, path.rng.uniform());
    const bool through = f.event == Media::Event::Through;
    const T tEnd = through ? (hit ? hit->t : ray.tMax) : T(f.distance / length);
    path.radiance += path.beta * emittersAlong(ray, d, tEnd, !hit && through, path, f.weight);
    path.beta *= f.weight;
    if (path.beta == glm::vec3(0.0f)) return false;
    if (f.event == Media::Event::Scattered) return scatter(path, ray(tEnd), d, f.phase, counters);
    if (f.event == Media::Event::Ground)
      return ground(path, glm::dvec3(ray.o) + f.distance * glm::dvec3(v), f.groundNormal, v, counters);
    return hit && surface(path, *hit, v, counters);
  }

  // The planet's ground under its air, where a ray that met no surface of the scene
  // comes down: a Lambertian surface of the atmosphere's ground albedo.
  bool ground(Path& path, const glm::dvec3& p, const glm::dvec3& n, const Vec3<T>& v, RayCounters& counters) const {
    SurfaceInteraction<T> si;
    si.p = Vec3<T>(p);
    si.n = si.ns = Vec3<T>(n);
    // Kilometres away, rounded to T: room to leave it by.
    si.pError = Vec3<T>(glm::abs(p) * (64.0 * double(std::numeric_limits<T>::epsilon())) + 1e-6);
    HitMaterial m;
    m.albedo = media_->groundAlbedo();
    m.ambient = 0.0f, m.diffuse = 1.0f, m.specular = 0.0f, m.reflection = 0.0f;
    return shade(path, si, m, false, v, counters);
  }

  // A scattering in a medium at p of a ray travelling along d: next-event
  // estimation through the media weighed by the phase function (MIS against it),
  // then the phase function's own direction, a bounce like a surface's.
  // Kept out of line: inlined into bounce, it slowed scenes without a medium by 6 %.
  [[gnu::noinline]] bool scatter(Path& path, const Vec3<T>& p, const glm::vec3& d, Phase phase,
                                 RayCounters& counters) const {
    if (path.depth > settings_.maxDepth) return false;
    if (settings_.mediumScatterings >= 0 && path.scatterings >= settings_.mediumScatterings) return false;
    ++path.scatterings;
    SurfaceInteraction<T> at;  // no surface: no normal, no error bound to leave by
    at.p = p;
    at.n = Vec3<T>(0);
    path.radiance += path.beta * sampleEveryLight(at, path.rng, [&](const LightSample<T>& ls, bool shadows) {
      return shadeInMedium(at, ls, shadows, d, phase, counters);
    });
    const glm::vec2 u = path.rng.uniform2();
    const glm::vec3 wi =
        Frame(d).toWorld(phase.rayleigh ? brdf::samplePhaseRayleigh(u) : brdf::samplePhaseHenyeyGreenstein(u, phase.g));
    path.countEmitters = false;
    path.bsdfPdf = phaseValue(phase, glm::dot(d, wi));  // the phase is its own density
    return continuePath(path, Ray<T>{p, Vec3<T>(wi)}, counters);
  }

  static float phaseValue(Phase phase, float cosine) {
    return phase.rayleigh ? brdf::phaseRayleigh(cosine) : brdf::phaseHenyeyGreenstein(cosine, phase.g);
  }

  glm::vec3 shadeInMedium(const SurfaceInteraction<T>& at, const LightSample<T>& ls, bool shadows, const glm::vec3& d,
                          Phase phase, RayCounters& counters) const {
    if (ls.value == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const float visible = shadows ? transmittance(at, ls, counters) : 1.0f;
    if (visible <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 through = mediumAlong(at.p, ls);
    if (through == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const float density = phaseValue(phase, glm::dot(d, ls.wi));
    const float weight = ls.pdf > 0.0f ? powerHeuristic(ls.pdf, density) : 1.0f;
    return ls.value * through * (density * weight * visible);
  }

  float transmittance(const SurfaceInteraction<T>& si, const LightSample<T>& ls, RayCounters& counters) const {
    return scene_.transmittance(ls.shadowRay(si), ls.toPoint ? &ls.target : nullptr, counters.shadow);
  }

  const RtScene& scene_;
  const EnvironmentLight& env_;
  const std::vector<PathLight>& lights_;
  bool coneSun_;
  const RenderSettings& settings_;
  PinholeCamera camera_;
  glm::dvec3 cameraPosition_;
  std::optional<Media> media_;  // fog, air, boxes: the truth of what the others blend in
  bool space_ = false;          // beyond the media is black space (a planet's air)
  float pixelSpread_ = 0.0f;
  // One per thread: a tracer serves one span at a time on each (renderTiles).
  static thread_local Batch batch_;
};

template <typename T, bool kMedium>
thread_local typename PathTracer<T, kMedium>::Batch PathTracer<T, kMedium>::batch_;

// Calls f with the tracer for the settings' precision and the scene's medium.
template <typename F>
auto withTracer(const RtScene& scene, const PathLights& lights, const RenderSettings& settings, F&& f) {
  const bool medium = Media::of(scene.fog(), scene.atmosphere(), scene.media()).has_value();
  if (settings.precision == Precision::Double) {
    return medium ? f(PathTracer<double, true>(scene, lights, settings)) : f(PathTracer<double, false>(scene, lights, settings));
  }
  return medium ? f(PathTracer<float, true>(scene, lights, settings)) : f(PathTracer<float, false>(scene, lights, settings));
}

RenderResult renderPathTraced(const RtScene& scene, const PathLights& lights, const RenderSettings& settings) {
  return withTracer(scene, lights, settings, [&](auto&& tracer) { return detail::renderTiles(tracer, settings); });
}

void pathTraceSpan(const RtScene& scene, const PathLights& lights, const RenderSettings& settings, int x0, int x1,
                   int y, glm::vec3* out, RayCounters& counters) {
  withTracer(scene, lights, settings, [&](auto&& tracer) { tracer.renderSpan(x0, x1, y, out, counters); });
}

glm::vec3 pathTracePixel(const RtScene& scene, const PathLights& lights, const RenderSettings& settings, int x, int y,
                         RayCounters& counters) {
  return withTracer(scene, lights, settings, [&](auto&& tracer) { return tracer.renderPixel(x, y, counters); });
}

glm::vec3 pathTraceRay(const RtScene& scene, const PathLights& lights, const RenderSettings& settings,
                       const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) {
  Pcg32 rng(mixBits(seed), 1);
  return withTracer(scene, lights, settings, [&](auto&& tracer) {
    if constexpr (std::decay_t<decltype(tracer)>::kDouble) {
      return tracer.Li(ray, rng, counters);
    } else {
      return tracer.Li(Ray<float>{Vec3<float>(ray.o), Vec3<float>(ray.d), float(ray.tMax)}, rng, counters);
    }
  });
}

}  // namespace

PathIntegrator::PathIntegrator(const RtScene& scene, RenderSettings settings)
    : IntegratorMethod(scene, std::move(settings)), lights_(preparePathLights(scene)) {}

RenderResult PathIntegrator::render() const { return renderPathTraced(scene(), *lights_, settings()); }

glm::vec3 PathIntegrator::renderPixel(int x, int y, RayCounters& counters) const {
  return pathTracePixel(scene(), *lights_, settings(), x, y, counters);
}

RenderSettings PathIntegrator::passSettings(int first, int count) const {
  RenderSettings pass = settings();
  pass.firstSample = first;
  pass.samplesPerPixel = count;
  pass.totalSamples = settings().samplesPerPixel;
  return pass;
}

glm::vec3 PathIntegrator::renderPixelSamples(int x, int y, int first, int count, RayCounters& counters) const {
  return pathTracePixel(scene(), *lights_, passSettings(first, count), x, y, counters);
}

void PathIntegrator::renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                                       RayCounters& counters) const {
  pathTraceSpan(scene(), *lights_, passSettings(first, count), x0, x1, y, out, counters);
}

glm::vec3 PathIntegrator::traceRay(const Ray<double>& ray, std::uint64_t seed, RayCounters& counters) const {
  return pathTraceRay(scene(), *lights_, settings(), ray, seed, counters);
}

}  // namespace engine::rt
