#pragma once
// Every participating medium of a scene as the CPU path tracer renders it: the fog
// (homogeneous, or an exponential height fog), the planet's atmosphere (the layers of
// shaders/common/atmosphere.glsl in spherical shells over a planet whose surface
// passes through y = 0) and boxes of fog (asset/scene_desc.h).
//
// Their optical depth along a ray is known, per channel: the fog's and the boxes' in
// closed form, the air's by four-point Gauss-Legendre quadrature over pieces of the ray short
// enough that its densities are nearly polynomial there (far below 1e-6 relative;
// Media.* test it against adaptive quadratures). So free flights are drawn as in a
// homogeneous medium (medium.h): the distance by one channel chosen at random, by
// inverting its optical depth, weighed over the three channels' densities (single
// sample MIS over the channels); shadow rays take the transmittance itself. No
// tracking noise, and no colour noise from paths that carry one channel.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "core/atmosphere.h"
#include "raytrace/medium.h"

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

  // A homogeneous fog alone: medium.h's closed forms, as before any other medium.
  const std::optional<Medium>& homogeneous() const { return homogeneous_; }
  bool hasPlanet() const { return air_.has_value(); }
  glm::vec3 groundAlbedo() const { return air_ ? air_->groundAlbedo : glm::vec3(0.0f); }

  enum class Event { Through, Scattered, Ground };
  struct Flight {
    Event event = Event::Through;
    double distance = 0.0;  // to the collision, the ground, or maxDistance
    // Scattered: the throughput's factor, scattering times transmittance over the
    // distance's density; else transmittance over the chance of getting there.
    glm::vec3 weight{1.0f};
    Phase phase;
    glm::dvec3 groundNormal{0.0};
  };
  // A free flight from o along the unit direction d, up to maxDistance (infinity:
  // until the ray leaves every medium, or meets the planet's ground). `uChannel`
  // picks the channel whose optical depth draws the distance, `u` draws it, `uPhase`
  // the medium that scatters where several do.
  Flight fly(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, float uChannel, float u, float uPhase) const;
  // What reaches o of light from o + distance d (none where the planet is in the way;
  // a homogeneous fog alone: medium.h's closed form).
  glm::vec3 transmittance(const glm::dvec3& o, const glm::dvec3& d, double distance) const;

  // At a point: the extinction and the scattering of all media there, per channel.
  struct Coefficients {
    glm::vec3 extinction{0.0f}, scattering{0.0f};
  };
  Coefficients at(const glm::dvec3& p) const;

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

  double end(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, bool* ground) const;
  // A ray and where it crosses a height fog's ceiling, the air's top and the ozone
  // tent's kinks: found once a ray, for every piece of it.
  struct Line {
    glm::dvec3 o, d;
    double cuts[9];
    int count;
  };
  Line lineOf(const glm::dvec3& o, const glm::dvec3& d) const;
  double pieceEnd(const Line& line, double t, double end) const;
  glm::dvec3 closedFormDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const;
  glm::dvec3 airDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const;
  glm::dvec3 pieceDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const;
  glm::dvec3 tailRate() const;
  glm::vec3 airExtinction(const glm::dvec3& p) const;
  double solve(const glm::dvec3& o, const glm::dvec3& d, double a, double b, int channel, double depth) const;
  Phase phaseAt(const glm::dvec3& p, float u, glm::vec3* scattering) const;
  std::optional<double> groundHit(const glm::dvec3& o, const glm::dvec3& d) const;
  double altitude(const glm::dvec3& p) const;
  // Calls f(extinction, scattering, phase) for each medium at p.
  template <typename F>
  void eachMedium(const glm::dvec3& p, F&& f) const;

  std::optional<Medium> homogeneous_;
  std::optional<Fog> fog_;
  std::optional<Air> air_;
  std::vector<Box> boxes_;
};

}  // namespace engine::rt
