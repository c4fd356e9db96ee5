#pragma once
// Every participating medium of a scene as the CPU path tracer renders it: the fog
// (homogeneous, or an exponential height fog), the planet's atmosphere (the layers of
// shaders/common/atmosphere.glsl in spherical shells over a planet whose surface
// passes through y = 0) and boxes of fog (asset/scene_desc.h).
//
// A fog alone, homogeneous, is drawn analytically over the three channels at once
// (medium.h). Anything else is tracked in one colour channel a path draws at its
// start (the path's throughput is then three times that channel's): delta tracking
// draws where it collides (Novak et al. 2018), against a majorant that bounds the
// extinction over each piece of the ray: the exponential layers' at the piece's
// lowest altitude, the ozone tent's at its peak where that lies in the piece, a
// box's where the piece meets it; unbiased however loose the bound, the pieces keep
// it tight. Shadow rays take the fog's and the boxes' optical depth in closed form
// and the air's by residual ratio tracking (Novak et al. 2014).
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "core/atmosphere.h"
#include "raytrace/medium.h"
#include "raytrace/rng.h"

namespace engine::rt {

// What a medium scatters with at a collision: Henyey-Greenstein's g, or Rayleigh's.
struct Phase {
  float g = 0.0f;
  bool rayleigh = false;
};

class Media {
 public:
  // The scene's media, or none when nothing scatters or absorbs between surfaces.
  static std::optional<Media> of(const FogDesc& fog, const AtmosphereDesc& atmosphere,
                                 const std::vector<MediumDesc>& boxes);

  // A homogeneous fog alone: drawn analytically over all three channels.
  const std::optional<Medium>& homogeneous() const { return homogeneous_; }
  bool tracked() const { return !homogeneous_.has_value(); }
  bool hasPlanet() const { return air_.has_value(); }
  glm::vec3 groundAlbedo() const { return air_ ? air_->groundAlbedo : glm::vec3(0.0f); }

  enum class Event { Through, Scattered, Absorbed, Ground };
  struct Flight {
    Event event = Event::Through;
    double distance = 0.0;  // to the collision, the ground, or maxDistance
    float weight = 1.0f;    // the channel's throughput factor: the albedo at a scattering
    Phase phase;
    glm::dvec3 groundNormal{0.0};
  };
  // Delta tracking in `channel` from o along the unit direction d, up to maxDistance
  // (infinity: until the ray leaves every medium, or meets the planet's ground).
  Flight track(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, int channel, Pcg32& rng) const;
  // Ratio tracking: what reaches o + distance d of light from there, in `channel`;
  // none where the planet is in the way.
  float transmittance(const glm::dvec3& o, const glm::dvec3& d, double distance, int channel, Pcg32& rng) const;

  // At a point, in `channel`: the extinction and the scattering of all media there;
  // and the phase of one of them, drawn by u in proportion to their scattering.
  struct Coefficients {
    float extinction = 0.0f, scattering = 0.0f;
  };
  Coefficients at(const glm::dvec3& p, int channel) const;
  Phase phaseAt(const glm::dvec3& p, int channel, float u) const;

 private:
  struct Box {
    glm::dvec3 min, max;
    glm::vec3 scattering, extinction;
    float g;
  };
  struct Air {
    atmospheretext::Atmosphere text;
    double bottom, top;  // radii
    glm::dvec3 center;
    glm::vec3 groundAlbedo;
  };
  struct Fog {
    glm::vec3 scattering, extinction;  // at y = 0
    float g;
    double falloff;  // per metre; 0: homogeneous
    double ceiling;  // where a height fog has thinned a billionfold: none above
  };
  struct Walk;

  double end(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, bool* ground) const;
  double majorant(double t0, double t1, const Walk& walk) const;
  double pieceEnd(double t, const Walk& walk) const;
  // Calls f(scattering, phase) for each medium at p, in `channel`; f returns true to stop.
  template <typename F>
  void eachScatterer(const glm::dvec3& p, int channel, F&& f) const;
  double closedFormDepth(const glm::dvec3& o, const glm::dvec3& d, double length, int channel) const;
  double airTransmittance(const glm::dvec3& o, const glm::dvec3& d, double length, int channel, Pcg32& rng) const;
  float airAt(const glm::dvec3& p, int channel) const;
  std::optional<double> groundHit(const glm::dvec3& o, const glm::dvec3& d) const;
  double altitude(const glm::dvec3& p) const;

  std::optional<Medium> homogeneous_;
  std::optional<Fog> fog_;
  std::optional<Air> air_;
  std::vector<Box> boxes_;
};

}  // namespace engine::rt
