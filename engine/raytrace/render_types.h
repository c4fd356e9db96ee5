#pragma once
// What a render is asked and what it gives back, whichever integrator makes it
// (integrator.h: the Whitted tracer of whitted_tracer.h, the path tracer of
// path_tracer.h, and the GPU's of gputrace/): the settings, the ray counts and
// progress, the linear framebuffer. tone_map.h turns that into an 8-bit image.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray.h"

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
  // Path: scatterings in media a path may take (1: single scattering, the light a
  // medium scatters once toward the camera; -1 as many as it meets).
  int mediumScatterings = -1;
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

}  // namespace engine::rt
