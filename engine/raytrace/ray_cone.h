#pragma once
// Ray cones (Akenine-Moeller et al., Ray Tracing Gems ch. 20), shared by the Whitted
// and the path tracer: a ray's footprint grows with distance, and at a hit it picks
// the textures' mipmap level as the rasterizer's screen-space derivatives do.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "raytrace/ray.h"
#include "raytrace/shapes.h"

namespace engine::rt {

// The footprint's width where the ray starts and its growth per unit of distance
// (radians); {0, 0}: the full-resolution level.
struct RayCone {
  float width = 0.0f;
  float spread = 0.0f;
};

// A camera sample's spread: a pixel's angle (the course camera's image plane at z = 1
// is 2 tan(fovy / 2) high), shared among the pixel's samples, which each cover 1 / spp
// of it.
inline float pixelConeSpread(double fovyDegrees, int height, int samplesPerPixel) {
  return float(2.0 * std::tan(glm::radians(fovyDegrees) / 2.0) /
               (double(std::max(1, height)) * std::sqrt(double(std::max(1, samplesPerPixel)))));
}

// Widens `cone` over the `distance` to the hit and returns the texture footprint there
// (as RtTexture::sample takes it). Foreshortening stretches the footprint along the
// slope by 1 / cos, and GL's isotropic level of detail takes the longer axis; `v` is
// the unit ray direction.
template <typename T>
float footprintAt(RayCone& cone, const SurfaceInteraction<T>& hit, const Vec3<T>& v, float distance) {
  cone.width += cone.spread * distance;
  const float cosine = std::max(float(std::abs(glm::dot(hit.n, v))), 1e-2f);
  return cone.width / cosine * hit.uvPerMetre;
}

}  // namespace engine::rt
