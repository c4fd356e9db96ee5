#pragma once
// The Whitted tracer's first hit eight camera samples at a time, for the course's
// scenes: spheres and planes, classic materials without textures, point, sun and area
// lights.
// Each lane runs the scalar tracer's operations in its order (the camera's double
// arithmetic, Sphere and Plane::intersect, the hit record, offsetRayOrigin, shadow rays,
// classicReflected), so every sample's colour is the scalar tracer's bit for bit;
// rays that leave a mirror go on in the scalar tracer (whitted_tracer.cpp), which has them
// at a few per cent of the samples. Rays in packets, the shapes tested against eight
// rays at once, shading out of the intersection loop: issue 14's course room.
//
// The lanes are eight pixels side by side at the same sample, each with its own random
// stream, so that an area light's shadow samples draw from each pixel's stream between
// its samples as the scalar tracer draws them.
//
// Compiled for AVX2 and used only where the CPU has it; elsewhere, and for any scene
// with something more (meshes, textures, PBR shading, transparency), the scalar tracer
// renders.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "raytrace/camera.h"
#include "raytrace/ray.h"
#include "raytrace/rng.h"

namespace engine::rt {

class RtScene;
struct ShapeLanes;
struct RenderSettings;

class WhittedPackets {
 public:
  static constexpr int kLanes = 8;

  // The packets for `scene` rendered with `settings`, or nothing where they do not
  // apply (see above) and the scalar tracer must render.
  static std::optional<WhittedPackets> create(const RtScene& scene, const RenderSettings& settings);
  // Why they do not apply (what --describe prints), or null where they do.
  static const char* unsupported(const RtScene& scene, const RenderSettings& settings);

  // What eight camera samples' first hits give the scalar tracer to finish, a lane
  // per sample: on a hit (bit i of `hits`), ambient, direct light and emission, the
  // distance travelled (fog), and the mirror's share (0: none) with the ray it goes on
  // along; where the sample escapes, the camera ray's direction (the environment).
  struct Lanes {
    int hits = 0;
    alignas(32) float r[kLanes], g[kLanes], b[kLanes], distance[kLanes], reflection[kLanes];
    alignas(32) float dx[kLanes], dy[kLanes], dz[kLanes];  // the camera rays' directions
    alignas(32) float ox[kLanes], oy[kLanes], oz[kLanes], rx[kLanes], ry[kLanes], rz[kLanes];  // the mirrors' rays

    glm::vec3 color(int i) const { return {r[i], g[i], b[i]}; }
    glm::vec3 direction(int i) const { return {dx[i], dy[i], dz[i]}; }
    Ray<float> reflected(int i) const { return Ray<float>{{ox[i], oy[i], oz[i]}, {rx[i], ry[i], rz[i]}}; }
  };

  // The samples at image points (px[i], py[i]) in pixels, i < count <= kLanes, as
  // PinholeCamera::generateRay and clippedToFarPlane make their rays. An area light's
  // shadow rays draw from rngs[i], in the scalar tracer's order. Adds the shadow rays
  // traced to `shadowRays`.
  void trace(const double* px, const double* py, int count, Pcg32* rngs, Lanes& out, std::uint64_t& shadowRays) const;

  // Public for the kernel's helpers only.
  struct MaterialTable {  // the classic model's weights, a field per vector
    std::vector<float> r, g, b, ambient, diffuse, specular, shininess, reflection, er, eg, eb;
  };
  struct Light {
    LightType type = LightType::Point;
    bool falloff = false, shadows = true;
    glm::vec3 position{0.0f};  // point: where it is; sun: its unit direction (toward the light); area: its centre
    glm::vec3 radiance{0.0f};  // colour * intensity
    glm::vec3 edgeU{0.0f}, edgeV{0.0f};  // area: the rectangle's edges
  };

 private:
  WhittedPackets(const PinholeCamera& camera) : camera_(camera) {}

  const ShapeLanes* shapes_ = nullptr;  // the scene's (RtScene::shapeLanes)
  MaterialTable materials_;
  std::vector<Light> lights_;
  PinholeCamera camera_;
  bool mirrors_ = false;  // whether reflections go on (maxDepth > 0)
  int shadowSamples_ = 1;  // an area light's N x N
};

}  // namespace engine::rt
