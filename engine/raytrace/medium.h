#pragma once
// A homogeneous participating medium filling the scene (a volumetric fog,
// asset/scene_desc.h's FogDesc), as the path tracer renders it: free-flight
// distances drawn by the extinction of one colour channel chosen at random and
// weighed by the mean of the three channels' densities (single-sample MIS over the
// channels, as pbrt-v4's volumetric path tracer does over wavelengths), transmittance
// for shadow rays, and scattering by Henyey-Greenstein's phase function
// (shaders/common/phase.glsl through core/phase.h).
#include <cmath>
#include <limits>
#include <optional>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"

namespace engine::rt {

struct Medium {
  glm::vec3 scattering{0.0f};  // per metre
  glm::vec3 extinction{0.0f};  // scattering + absorption, per metre
  float anisotropy = 0.0f;     // Henyey-Greenstein's g

  // The scene's medium: its volumetric fog, or none.
  static std::optional<Medium> of(const FogDesc& fog) {
    if (!fog.enabled || fog.model != FogModel::Volumetric) return std::nullopt;
    return Medium{fog.scattering, fog.scattering + fog.absorption, fog.anisotropy};
  }

  // What remains of light over `distance` metres (infinite: none, but in a channel
  // that nothing extinguishes).
  glm::vec3 transmittance(double distance) const {
    glm::vec3 t(1.0f);
    for (int c = 0; c < 3; ++c)
      if (extinction[c] > 0.0f) t[c] = float(std::exp(-double(extinction[c]) * distance));
    return t;
  }

  // One free flight along a ray that meets a surface (or the far plane, or nothing:
  // infinity) `maxDistance` metres on. `uChannel` picks the channel whose extinction
  // draws the distance, `u` draws it. Scattered: at `distance`, the path's throughput
  // times `weight` (scattering times transmittance over the distance's density).
  // Not: the ray reaches maxDistance, its throughput times `weight` (transmittance
  // over the chance of getting there). Each estimate is unbiased for every channel.
  struct Flight {
    bool scattered = false;
    double distance = 0.0;
    glm::vec3 weight{1.0f};
  };
  Flight fly(double maxDistance, float uChannel, float u) const {
    const int c = std::min(2, int(uChannel * 3.0f));
    Flight f;
    f.distance = extinction[c] > 0.0f ? -std::log1p(-double(u)) / double(extinction[c])
                                      : std::numeric_limits<double>::infinity();
    f.scattered = f.distance < maxDistance;
    if (!f.scattered) f.distance = maxDistance;
    const glm::vec3 tr = transmittance(f.distance);
    const glm::vec3 density = f.scattered ? extinction * tr : tr;
    const float mean = (density.x + density.y + density.z) / 3.0f;
    f.weight = mean > 0.0f ? (f.scattered ? scattering * tr : tr) / mean : glm::vec3(0.0f);
    return f;
  }
};

}  // namespace engine::rt
