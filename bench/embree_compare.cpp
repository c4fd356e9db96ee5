// Our BVH against Embree 3, the yardstick: the same triangles, the same rays.
//
// For each scene the triangles are those the ray tracer's BVH holds (scene_builder:
// boxes, skinned characters posed at --time, the terrain as CDLOD selects it for a
// 720-line image), plus the analytic spheres and planes tessellated (UV spheres of
// 128 x 64 quads, planes as squares of their extent or the camera's far distance),
// so that the Cornell room, which has no triangles of its own, has something to
// trace. Both structures get the triangles in the same order, so a triangle index is
// an Embree primID.
//
// Rays are made once, by our code: the camera's primary rays through the pixel
// centres of a 1280 x 720 image, then from each primary hit (found by our BVH) a
// shadow ray towards the first light when the surface faces it (as the integrator
// does: offset origin, tMax 1 on target - origin for a point light). Both are traced
// with our Bvh::intersect / intersectAny and Embree's single-ray rtcIntersect1 /
// rtcOccluded1 (default scene flags, so not the ROBUST mode; build quality MEDIUM and
// HIGH), on 1 thread and on every core (TBB over chunks of 1024 rays, the same
// harness for both). Times are medians of --runs runs; a check pass counts how many
// rays agree (same triangle, or t within 1e-4 relative, or both miss; any-hit: same
// answer).
//
// Primary rays also go in packets of eight, a 4 x 2 block of pixels each: ours through
// Bvh::intersect8, Embree's through rtcIntersect8 (its packet kernels), the same
// packets on both sides and the same harness (chunks of 128 packets).
//
// Build times last: ours and Embree's MEDIUM and HIGH, each on 1 thread and on every
// core (ours in a TBB arena of that many threads; its tree is the same either way).
//
//   build/bin/embree_compare [--runs N] [--time T] [--width W --height H] [--isa sse2|avx2|avx512]
//                            [--embree-isa ISA] [scene.json ...]
//
// Embree picks its kernels by the CPU: on an AVX-512 machine a BVH8 with four-triangle
// leaves and AVX-512 code; --embree-isa sse4.2 (Embree's max_isa) holds it to SSE and
// a BVH4. --isa picks ours (default: the best the CPU has; avx512 is our AVX2 code
// compiled with AVX-512VL's registers, see bvh.h).
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <functional>
#include <numbers>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asset/scene_file.h"
#include "raytrace/bvh.h"
#include "raytrace/camera.h"
#include "raytrace/scene_builder.h"

namespace {

namespace rt = engine::rt;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
  int runs = 5;
  double time = 1.0;
  int width = 1280, height = 720;
  std::vector<std::string> scenes;
  std::string embreeIsa;  // Embree's max_isa; empty: the best the CPU has
};

void addSphere(const glm::dvec3& c, double r, std::vector<rt::TriangleVerts>& out) {
  constexpr int kU = 128, kV = 64;
  const auto at = [&](int i, int j) {
    const double phi = 2.0 * std::numbers::pi * i / kU, theta = std::numbers::pi * j / kV;
    return glm::vec3(c + r * glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
  };
  for (int j = 0; j < kV; ++j) {
    for (int i = 0; i < kU; ++i) {
      const glm::vec3 a = at(i, j), b = at(i + 1, j), d = at(i, j + 1), e = at(i + 1, j + 1);
      if (j > 0) out.push_back({a, b, e});
      if (j + 1 < kV) out.push_back({a, e, d});
    }
  }
}

void addPlane(const glm::dvec3& point, const glm::dvec3& normal, double extent, std::vector<rt::TriangleVerts>& out) {
  const glm::dvec3 n = glm::normalize(normal);
  const glm::dvec3 u = glm::normalize(std::abs(n.y) < 0.9 ? glm::cross(n, glm::dvec3(0, 1, 0)) : glm::cross(n, glm::dvec3(1, 0, 0)));
  const glm::dvec3 v = glm::cross(n, u);
  const auto at = [&](double s, double t) { return glm::vec3(point + extent * (s * u + t * v)); };
  out.push_back({at(-1, -1), at(1, -1), at(1, 1)});
  out.push_back({at(-1, -1), at(1, 1), at(-1, 1)});
}

// The BVH's triangles (meshes in order, as RtScene gathers them), then the analytic shapes.
std::vector<rt::TriangleVerts> sceneTriangles(const engine::SceneDesc& desc, const rt::RtScene& scene) {
  std::vector<rt::TriangleVerts> tris;
  for (const rt::RtMesh& m : scene.meshes()) {
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      tris.push_back({m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]]});
    }
  }
  for (const engine::PrimitiveDesc& p : desc.primitives) {
    if (p.type == engine::PrimitiveType::Sphere) addSphere(p.center, p.radius, tris);
    if (p.type == engine::PrimitiveType::Plane) addPlane(p.point, p.normal, p.extent > 0 ? p.extent : desc.camera.farPlane, tris);
  }
  return tris;
}

struct RaySets {
  std::vector<rt::Ray<float>> primary, shadow;
  std::vector<rt::Ray<float>> packets;  // the primary rays again, 4 x 2 pixel blocks in turn
};

// The primary rays regrouped into 4 x 2 pixel blocks, eight consecutive rays each; the
// image's edges padded with copies of their last ray.
std::vector<rt::Ray<float>> packetOrder(const std::vector<rt::Ray<float>>& primary, int width, int height) {
  std::vector<rt::Ray<float>> out;
  for (int by = 0; by < height; by += 2) {
    for (int bx = 0; bx < width; bx += 4) {
      for (int i = 0; i < 8; ++i) {
        const int x = std::min(bx + i % 4, width - 1), y = std::min(by + i / 4, height - 1);
        out.push_back(primary[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
      }
    }
  }
  return out;
}

RaySets makeRays(const engine::SceneDesc& desc, const rt::Bvh& bvh, const std::vector<rt::TriangleVerts>& tris,
                 const Options& o) {
  RaySets sets;
  const rt::PinholeCamera camera(desc.camera, o.width, o.height);
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) sets.primary.push_back(camera.generateRay<float>(x + 0.5, y + 0.5));
  }
  sets.packets = packetOrder(sets.primary, o.width, o.height);
  if (desc.lights.empty()) return sets;
  const engine::LightDesc& light = desc.lights.front();
  for (const auto& ray : sets.primary) {
    const auto hit = bvh.intersect(ray);
    if (!hit) continue;
    const rt::TriangleVerts& t = tris[hit->triangle];
    const rt::SurfaceInteraction<float> si = rt::triangleInteraction(hit->hit, t.p0, t.p1, t.p2);
    const glm::vec3 n = glm::dot(si.n, ray.d) > 0.0f ? -si.n : si.n;
    if (light.type == engine::LightType::Sun) {
      const glm::vec3 wi = glm::normalize(glm::vec3(light.direction));
      if (glm::dot(n, wi) > 0.0f) sets.shadow.push_back(si.spawnRay(wi));
    } else {
      const glm::vec3 target(light.position);
      if (glm::dot(n, target - si.p) > 0.0f) sets.shadow.push_back(si.spawnRayTo(target, 1.0f));
    }
  }
  return sets;
}

struct Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  Embree(const std::vector<rt::TriangleVerts>& tris, int threads, RTCBuildQuality quality, const std::string& isa) {
    std::string config = "threads=" + std::to_string(threads);
    if (!isa.empty()) config += ",max_isa=" + isa;
    device = rtcNewDevice(config.c_str());
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
    std::memcpy(v, tris.data(), tris.size() * sizeof(rt::TriangleVerts));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
    for (unsigned i = 0; i < 3 * tris.size(); ++i) idx[i] = i;
    rtcSetGeometryBuildQuality(geom, quality);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
  }
  Embree(const Embree&) = delete;
  Embree& operator=(const Embree&) = delete;
  ~Embree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  double commit() {
    const auto start = Clock::now();
    rtcCommitScene(scene);
    return seconds(start);
  }

  static RTCRayHit toRtc(const rt::Ray<float>& r) {
    RTCRayHit rh{};
    rh.ray.org_x = r.o.x, rh.ray.org_y = r.o.y, rh.ray.org_z = r.o.z;
    rh.ray.dir_x = r.d.x, rh.ray.dir_y = r.d.y, rh.ray.dir_z = r.d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = r.tMax;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
  }
  // primID and t, or ~0u when nothing is hit.
  std::pair<unsigned, float> nearest(const rt::Ray<float>& r) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = toRtc(r);
    rtcIntersect1(scene, &ctx, &rh);
    return {rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? ~0u : rh.hit.primID, rh.ray.tfar};
  }
  // Eight rays through rtcIntersect8; the mask of those that hit.
  unsigned nearest8(const rt::Ray<float>* r, unsigned* prims = nullptr, float* ts = nullptr) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    alignas(32) RTCRayHit8 rh;
    alignas(32) int valid[8];
    for (int i = 0; i < 8; ++i) {
      valid[i] = -1;
      rh.ray.org_x[i] = r[i].o.x, rh.ray.org_y[i] = r[i].o.y, rh.ray.org_z[i] = r[i].o.z;
      rh.ray.dir_x[i] = r[i].d.x, rh.ray.dir_y[i] = r[i].d.y, rh.ray.dir_z[i] = r[i].d.z;
      rh.ray.tnear[i] = 0.0f;
      rh.ray.tfar[i] = r[i].tMax;
      rh.ray.mask[i] = ~0u;
      rh.ray.time[i] = 0.0f;
      rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, scene, &ctx, &rh);
    unsigned mask = 0;
    for (int i = 0; i < 8; ++i) {
      const bool hit = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
      mask |= unsigned(hit) << i;
      if (prims) prims[i] = hit ? rh.hit.primID[i] : ~0u;
      if (ts) ts[i] = rh.ray.tfar[i];
    }
    return mask;
  }
  bool occluded(const rt::Ray<float>& r) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = toRtc(r);
    rtcOccluded1(scene, &ctx, &rh.ray);
    return rh.ray.tfar < 0.0f;
  }
};

// One pass of `trace` over every ray on `threads` workers: its seconds.
double traceOnce(const std::vector<rt::Ray<float>>& rays, int threads,
                 const std::function<bool(const rt::Ray<float>&)>& trace) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  std::vector<char> sink(rays.size());
  const auto start = Clock::now();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) sink[i] = trace(rays[i]);
  });
  return seconds(start);
}

// The same over packets of eight consecutive rays.
double packetsOnce(const std::vector<rt::Ray<float>>& rays, int threads,
                   const std::function<unsigned(const rt::Ray<float>*)>& trace) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  std::vector<unsigned> sink(rays.size() / 8);
  const auto start = Clock::now();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sink.size(), 128), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) sink[i] = trace(&rays[8 * i]);
  });
  return seconds(start);
}

// Each pass once a run, in turn, for `runs` runs, each run starting one pass later so
// that none always follows the same one. The passes of one run are a fraction of a
// second apart, so a ratio taken within a run is free of the host's slower and faster
// spells (these machines' speed drifts by a third over minutes), where a ratio of
// medians taken minutes apart is not. Per pass: its median seconds, and the median
// over the runs of pass 0's seconds over its own (its speed relative to pass 0's).
struct Interleaved {
  std::vector<double> seconds;
  std::vector<double> speedOverFirst;
};

Interleaved interleaved(int runs, const std::vector<std::function<double()>>& passes) {
  const std::size_t n = passes.size();
  std::vector<std::vector<double>> times(n), ratios(n);
  for (int r = 0; r < runs; ++r) {
    std::vector<double> run(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t p = (std::size_t(r) + k) % n;
      run[p] = passes[p]();
    }
    for (std::size_t p = 0; p < n; ++p) {
      times[p].push_back(run[p]);
      ratios[p].push_back(run[0] / run[p]);
    }
  }
  Interleaved result;
  for (std::size_t p = 0; p < n; ++p) {
    result.seconds.push_back(median(times[p]));
    result.speedOverFirst.push_back(median(ratios[p]));
  }
  return result;
}

double mrays(std::size_t n, double s) { return double(n) / s / 1e6; }

// Primary rays in packets of eight: ours (intersect8) against rtcIntersect8, agreement
// as for single rays, and our single-ray speed on the same rays for the gain.
void printPacketRows(const std::string& name, std::size_t triangles, const rt::Bvh& bvh, const Embree& medium,
                     const Embree& high, const std::vector<rt::Ray<float>>& rays, int runs, int cores) {
  std::size_t agree = 0;
  for (std::size_t i = 0; i < rays.size(); i += 8) {
    std::array<rt::BvhHit<float>, 8> ours{};
    const unsigned mask = bvh.intersect8(std::span<const rt::Ray<float>, 8>(&rays[i], 8), ours);
    unsigned prims[8];
    float ts[8];
    const unsigned theirs = high.nearest8(&rays[i], prims, ts);
    for (int k = 0; k < 8; ++k) {
      const bool a = (mask >> k) & 1u, b = (theirs >> k) & 1u;
      const auto& h = ours[std::size_t(k)];
      agree += (!a && !b) ||
               (a && b && (h.triangle == prims[k] || std::abs(h.hit.t - ts[k]) <= 1e-4f * std::max(1.0f, ts[k])));
    }
  }
  for (int threads : {1, cores}) {
    const Interleaved t = interleaved(runs, {
        [&] {
          return packetsOnce(rays, threads, [&](const rt::Ray<float>* r) {
            std::array<rt::BvhHit<float>, 8> hits;
            return bvh.intersect8(std::span<const rt::Ray<float>, 8>(r, 8), hits);
          });
        },
        [&] { return traceOnce(rays, threads, [&](const rt::Ray<float>& r) { return bvh.intersect(r).has_value(); }); },
        [&] { return packetsOnce(rays, threads, [&](const rt::Ray<float>* r) { return medium.nearest8(r); }); },
        [&] { return packetsOnce(rays, threads, [&](const rt::Ray<float>* r) { return high.nearest8(r); }); },
    });
    const double ours = t.seconds[0], single = t.seconds[1], em = t.seconds[2], eh = t.seconds[3];
    std::printf("| %s | %zu | primary packets of 8 %zu | %d | %.2f | %.2f | %.2f | %.2f | %.3f%% |\n", name.c_str(), triangles,
                rays.size(), threads, mrays(rays.size(), ours), mrays(rays.size(), em), mrays(rays.size(), eh),
                1.0 / t.speedOverFirst[3], 100.0 * double(agree) / double(rays.size()));
    std::printf("|   | | (ours one ray at a time on the same rays: %.2f Mrays/s; packets %.2fx that) | | | | | | |\n",
                mrays(rays.size(), single), 1.0 / t.speedOverFirst[1]);
    std::fflush(stdout);
  }
}

int run(const Options& o) {
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("| scene | triangles | rays | threads | ours Mrays/s | Embree MEDIUM | Embree HIGH | ours / HIGH | agree |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> buildLines;
  for (const std::string& path : o.scenes) {
    auto desc = engine::loadSceneFile(path);
    if (!desc) {
      std::fprintf(stderr, "embree_compare: %s\n", desc.error().message.c_str());
      return 2;
    }
    auto scene = rt::buildRtScene(*desc, o.time, o.height);
    if (!scene) {
      std::fprintf(stderr, "embree_compare: %s\n", scene.error().message.c_str());
      return 2;
    }
    const std::vector<rt::TriangleVerts> tris = sceneTriangles(*desc, *scene);
    const std::string name = path.substr(path.find_last_of('/') + 1);

    // Our build on 1 and every thread (the same tree either way), as Embree's below.
    rt::Bvh bvh;
    std::vector<double> ourBuild[2];
    for (int t = 0; t < 2; ++t) {
      for (int r = 0; r < std::max(1, o.runs / 2); ++r) {
        tbb::task_arena(t == 0 ? 1 : cores).execute([&] {
          const auto start = Clock::now();
          bvh.build(tris);
          ourBuild[t].push_back(seconds(start));
        });
      }
    }
    const RaySets rays = makeRays(*desc, bvh, tris, o);
    // Build times for both qualities on 1 and every thread; the HIGH ones are kept.
    std::vector<double> builds[2][2];
    for (int q = 0; q < 2; ++q) {
      for (int t = 0; t < 2; ++t) {
        for (int r = 0; r < std::max(1, o.runs / 2); ++r) {
          Embree e(tris, t == 0 ? 1 : cores, q == 0 ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH, o.embreeIsa);
          builds[q][t].push_back(e.commit());
        }
      }
    }
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %zu | %.0f / %.0f | %.0f / %.0f | %.0f / %.0f |", name.c_str(), tris.size(),
                  1e3 * median(ourBuild[0]), 1e3 * median(ourBuild[1]), 1e3 * median(builds[0][0]), 1e3 * median(builds[0][1]),
                  1e3 * median(builds[1][0]), 1e3 * median(builds[1][1]));
    buildLines.push_back(line);
    Embree medium(tris, cores, RTC_BUILD_QUALITY_MEDIUM, o.embreeIsa), high(tris, cores, RTC_BUILD_QUALITY_HIGH, o.embreeIsa);
    medium.commit();
    high.commit();

    // Agreement, once, outside the timed passes.
    std::size_t agreeNearest = 0, agreeAny = 0;
    for (const auto& r : rays.primary) {
      const auto ours = bvh.intersect(r);
      const auto [prim, t] = high.nearest(r);
      if (!ours && prim == ~0u) ++agreeNearest;
      if (ours && prim != ~0u &&
          (ours->triangle == prim || std::abs(ours->hit.t - t) <= 1e-4f * std::max(1.0f, t))) {
        ++agreeNearest;
      }
    }
    for (const auto& r : rays.shadow) agreeAny += bvh.intersectAny(r) == high.occluded(r);

    for (int kind = 0; kind < 2; ++kind) {
      const auto& set = kind == 0 ? rays.primary : rays.shadow;
      if (set.empty()) continue;
      const double agree = double(kind == 0 ? agreeNearest : agreeAny) / double(set.size());
      for (int threads : {1, cores}) {
        const auto ourPass = [&, threads](rt::Bvh::Isa isa) {
          return [&, threads, isa] {
            const rt::Bvh::Isa chosen = rt::Bvh::isa();
            rt::Bvh::setIsa(isa);
            const double t = kind == 0 ? traceOnce(set, threads, [&](const rt::Ray<float>& r) { return bvh.intersect(r).has_value(); })
                                       : traceOnce(set, threads, [&](const rt::Ray<float>& r) { return bvh.intersectAny(r); });
            rt::Bvh::setIsa(chosen);
            return t;
          };
        };
        const auto embreePass = [&, threads](const Embree& e) {
          return [&, threads] {
            return kind == 0 ? traceOnce(set, threads, [&](const rt::Ray<float>& r) { return e.nearest(r).first != ~0u; })
                             : traceOnce(set, threads, [&](const rt::Ray<float>& r) { return e.occluded(r); });
          };
        };
        // On an AVX-512 CPU our AVX2 compile runs too, for what the wider one gains.
        const bool alsoAvx2 = rt::Bvh::isa() == rt::Bvh::Isa::kAvx512;
        std::vector<std::function<double()>> passes = {ourPass(rt::Bvh::isa()), embreePass(medium), embreePass(high)};
        if (alsoAvx2) passes.push_back(ourPass(rt::Bvh::Isa::kAvx2));
        const Interleaved t = interleaved(o.runs, passes);
        const double ours = t.seconds[0], em = t.seconds[1], eh = t.seconds[2];
        std::printf("| %s | %zu | %s %zu | %d | %.2f | %.2f | %.2f | %.2f | %.3f%% |\n", name.c_str(), tris.size(),
                    kind == 0 ? "primary (nearest)" : "shadow (any)", set.size(), threads, mrays(set.size(), ours),
                    mrays(set.size(), em), mrays(set.size(), eh), 1.0 / t.speedOverFirst[2], 100.0 * agree);
        if (alsoAvx2) {
          std::printf("|   | | (ours compiled for AVX2 alone: %.2f Mrays/s; with AVX-512VL %.2fx that) | | | | | | |\n",
                      mrays(set.size(), t.seconds[3]), 1.0 / t.speedOverFirst[3]);
        }
        std::fflush(stdout);
      }
    }
    printPacketRows(name, tris.size(), bvh, medium, high, rays.packets, o.runs, cores);
  }
  std::printf("\nBuild times, ms (median; 1 thread / %d threads):\n\n", cores);
  std::printf("| scene | triangles | ours | Embree MEDIUM | Embree HIGH |\n|---|---:|---:|---:|---:|\n");
  for (const auto& l : buildLines) std::printf("%s\n", l.c_str());
  return 0;
}

std::optional<rt::Bvh::Isa> isaNamed(const std::string& name) {
  if (name == "sse2") return rt::Bvh::Isa::kSse2;
  if (name == "avx2") return rt::Bvh::Isa::kAvx2;
  if (name == "avx512") return rt::Bvh::Isa::kAvx512;
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "embree_compare: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--runs") {
      o.runs = std::max(1, std::atoi(value()));
    } else if (a == "--time") {
      o.time = std::atof(value());
    } else if (a == "--width") {
      o.width = std::max(1, std::atoi(value()));
    } else if (a == "--height") {
      o.height = std::max(1, std::atoi(value()));
    } else if (a == "--isa") {
      const std::string isa = value();
      const auto wanted = isaNamed(isa);
      if (!wanted) {
        std::fprintf(stderr, "embree_compare: --isa takes sse2, avx2 or avx512, not %s\n", isa.c_str());
        return 2;
      }
      rt::Bvh::setIsa(*wanted);
      if (rt::Bvh::isa() != *wanted) {
        std::fprintf(stderr, "embree_compare: this CPU has no %s\n", rt::Bvh::isaName(*wanted));
        return 2;
      }
    } else if (a == "--embree-isa") {
      o.embreeIsa = value();
    } else if (a.starts_with("--")) {
      std::fprintf(stderr, "embree_compare: unknown option %s\n", a.c_str());
      return 2;
    } else {
      o.scenes.push_back(a);
    }
  }
  if (o.scenes.empty()) o.scenes = {"assets/scenes/cornell.json", "assets/scenes/demo.json"};
  std::printf("Embree %d.%d.%d (max_isa %s) vs engine::rt::Bvh (%s), %dx%d, --runs %d --time %g\n\n",
              RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH,
              o.embreeIsa.empty() ? "the CPU's best" : o.embreeIsa.c_str(),
              rt::Bvh::isaName(rt::Bvh::isa()), o.width, o.height, o.runs, o.time);
  return run(o);
}
