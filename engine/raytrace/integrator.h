#pragma once
// The Whitted-style integrator of the course: primary rays through stratified pixel
// samples, direct light from point, sun and rectangular area lights with shadow rays,
// perfect mirror reflection to a maximum depth, sky or background for rays that escape.
// Shading::Classic is the course's model; Shading::Pbr a Lambert + GGX one. The output
// is a linear float RGB framebuffer; tone_map.h turns it into an 8-bit image.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray.h"
#include "raytrace/rt_scene.h"

namespace engine::rt {

struct RayCounters {
  std::uint64_t primary = 0;
  std::uint64_t shadow = 0;
  std::uint64_t reflection = 0;  // Whitted: mirror rays; path: every bounce ray

  std::uint64_t total() const { return primary + shadow + reflection; }
  RayCounters& operator+=(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflection += o.reflection;
    return *this;
  }
};

struct RenderProgress {
  int tilesDone = 0;
  int tilesTotal = 0;
  RayCounters rays;  // so far
  double seconds = 0.0;
};

// Whitted: the course's tracer (direct light, mirrors, ambient). Path: the physically
// based path tracer of path_tracer.h, the ground truth.
enum class Method { Whitted, Path };

struct RenderSettings {
  Method method = Method::Whitted;
  int width = 640;
  int height = 480;
  int samplesPerPixel = 1;  // Whitted: 1 the pixel centre, N stratified jittered samples
  int firstSample = 0;      // path: the samples rendered are [firstSample, firstSample + spp)
  // Path: the samples the whole image gets, when spp is only one pass of them (the
  // progressive window): each sample's ray cone is its share of the pixel, so a
  // pass must use the whole image's share to sum to the image render() makes. 0: spp.
  int totalSamples = 0;
  int shadowSamples = 4;    // an area light gets N x N stratified jittered shadow rays
  int maxDepth = 5;         // bounces after the primary hit (Whitted: mirror and transmitted rays; path: 0 is direct light only)
  int rouletteDepth = 3;    // path: Russian roulette from this bounce on
  std::uint64_t seed = 1;
  Precision precision = Precision::Float;
  int threads = 0;          // 0: TBB's default (every core); N: at most N workers
  int tileSize = 16;
  // Called after each finished tile, one call at a time (the integrator serialises
  // them), from whichever worker finished it. Return false to stop the render early.
  std::function<bool(const RenderProgress&)> progress;
};

// Linear RGB, top row first.
struct Framebuffer {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;

  Framebuffer() = default;
  Framebuffer(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h), glm::vec3(0.0f)) {}
  glm::vec3& at(int x, int y) { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
  const glm::vec3& at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

struct RenderResult {
  Framebuffer image;
  RayCounters rays;
  double seconds = 0.0;
  bool cancelled = false;
};

struct PathLights;
class WhittedPackets;

class Integrator {
 public:
  // The scene must outlive the integrator and stay unchanged while it renders.
  Integrator(const RtScene& scene, RenderSettings settings);

  // Renders every pixel over 16 x 16 tiles in parallel (TBB).
  RenderResult render() const;
  // One pixel's linear colour, exactly as render() computes it (same RNG stream).
  glm::vec3 renderPixel(int x, int y, RayCounters* counters = nullptr) const;
  // The path tracer's mean of samples [first, first + count) of a pixel (a pass of a
  // progressive render); the Whitted tracer's renderPixel, whatever first and count.
  glm::vec3 renderPixelSamples(int x, int y, int first, int count, RayCounters* counters = nullptr) const;
  // renderPixelSamples of pixels x0 .. x1 - 1 of row y into out[0 ..], traced as
  // render() traces a tile's row (the Whitted tracer's packets, the path tracer's
  // paths side by side): the same colours, faster than pixel by pixel. What the
  // window's progressive trace calls.
  void renderSpanSamples(int x0, int x1, int y, int first, int count, glm::vec3* out,
                         RayCounters* counters = nullptr) const;
  // The radiance along one ray (as a reflected ray at depth 0 would see it), in the
  // chosen precision; the RNG for area-light samples is seeded from `seed`.
  glm::vec3 traceRay(const Ray<double>& ray, std::uint64_t seed = 0, RayCounters* counters = nullptr) const;

  const RenderSettings& settings() const { return settings_; }
  // Whether the Whitted tracer, where its packets do not apply, finds each row's
  // camera rays' first hits eight at a time (integrator.cpp's SpanTracer): float
  // precision on a CPU with AVX2. render(), renderSpanSamples() and describe() ask it.
  static bool firstHitsInRows(const RenderSettings& settings);

 private:
  const RtScene* scene_;
  RenderSettings settings_;
  std::shared_ptr<const PathLights> pathLights_;  // Method::Path only
  // The Whitted tracer's packets, where they apply (whitted_packets.h).
  std::shared_ptr<const WhittedPackets> packets_;
  // settings_ for samples [first, first + count) of the path tracer's pixels.
  RenderSettings passSettings(int first, int count) const;
};

}  // namespace engine::rt
