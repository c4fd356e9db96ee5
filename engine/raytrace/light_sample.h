#pragma once
// The path tracer's light samples (path_tracer.cpp): a direction toward a light with
// what arrives along it, drawn for every kind of light; and whether a ray crosses an
// area light, for the paths that find one by themselves.
#include <glm/glm.hpp>

#include "core/spot_cone.h"
#include "raytrace/path_lights.h"
#include "raytrace/ray.h"
#include "raytrace/sampling.h"
#include "raytrace/shapes.h"

namespace engine::rt {

// A direction toward a light with what arrives along it: `value` is the radiance
// divided by the sample's pdf, or for a delta light the radiance-equivalent that
// f * cos * value is its contribution (pi I, pi I / d^2).
// The shadow ray is made only once the BSDF says the sample matters: toward `target`
// (a point or area light), or along wi to infinity.
template <typename T>
struct LightSample {
  glm::vec3 wi{0.0f};
  glm::vec3 value{0.0f};
  float pdf = 0.0f;  // solid angle; 0 for a delta
  bool toPoint = false;
  Vec3<T> target{0};

  Ray<T> shadowRay(const SurfaceInteraction<T>& si) const {
    return toPoint ? si.spawnRayTo(target, T(1)) : si.spawnRay(Vec3<T>(wi));
  }
};

// Whether the ray crosses the rectangle's emitting side before tHit; its
// solid-angle density as a light sample there, and its distance.
template <typename T>
inline bool hitsArea(const PathLight& l, const Ray<T>& ray, const glm::vec3& d, T tHit, float* pdf, double* distance) {
  if (l.area <= 0.0f) return false;
  const float cosLight = -glm::dot(d, l.normal);
  if (cosLight <= 0.0f) return false;
  const glm::dvec3 o(ray.o), dir(ray.d), n(l.normal);
  const double t = glm::dot(l.position - o, n) / glm::dot(dir, n);
  if (!(t > 0.0) || t >= double(tHit)) return false;
  const glm::dvec3 q = o + t * dir - l.position;
  const double a = glm::dot(q, l.edgeU) / glm::dot(l.edgeU, l.edgeU);
  const double b = glm::dot(q, l.edgeV) / glm::dot(l.edgeV, l.edgeV);
  if (std::abs(a) > 0.5 || std::abs(b) > 0.5) return false;
  *distance = t * glm::length(dir);
  *pdf = float(*distance * *distance / (double(l.area) * double(cosLight)));
  return true;
}

// False when the light cannot reach the point (behind an area light, at the light).
template <typename T>
[[gnu::always_inline]] inline bool sampleLight(const SurfaceInteraction<T>& si, const PathLight& l, glm::vec2 u, LightSample<T>& ls) {
  switch (l.type) {
    case LightType::Sun:
      if (l.cosMax < 1.0f) {
        ls.wi = Frame(l.direction).toWorld(sampleUniformCone(u, l.cosMax));
        ls.pdf = uniformConePdf(l.cosMax);
        ls.value = l.radiance / ls.pdf;
      } else {
        ls.wi = l.direction;
        ls.value = l.power * kPi;
      }
      return true;
    case LightType::Point:
    case LightType::Spot: {
      ls.toPoint = true;
      ls.target = Vec3<T>(l.position);
      const Vec3<T> toLight = ls.target - si.p;
      const T d2 = glm::dot(toLight, toLight);
      if (!(d2 > T(0))) return false;
      ls.wi = glm::vec3(dividedBy(toLight, std::sqrt(d2)));
      // A point's cone holds every direction: its weight is exactly 1.
      ls.value = l.power * (kPi / (l.falloff ? float(d2) : 1.0f)) *
                 spottext::spotAttenuation(glm::dot(ls.wi, l.direction), l.cosOuter, l.cosInner);
      return true;
    }
    case LightType::Area: {
      if (l.area <= 0.0f) return false;
      ls.toPoint = true;
      ls.target = Vec3<T>(l.position + (double(u.x) - 0.5) * l.edgeU + (double(u.y) - 0.5) * l.edgeV);
      const Vec3<T> toLight = ls.target - si.p;
      const T d2 = glm::dot(toLight, toLight);
      if (!(d2 > T(0))) return false;
      ls.wi = glm::vec3(dividedBy(toLight, std::sqrt(d2)));
      const float cosLight = -glm::dot(ls.wi, l.normal);
      if (cosLight <= 0.0f) return false;
      ls.pdf = float(d2) / (l.area * cosLight);
      ls.value = l.power / ls.pdf;
      return true;
    }
  }
  return false;
}

}  // namespace engine::rt
