#include "raytrace/media.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace engine::rt {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Where a height fog has thinned a billionfold (exp(-20.72)): nothing above, so that
// a ray rising through it ends its tracking (the light lost to what is left there is
// below a billionth of what the fog holds).
constexpr double kFogCeilingDepth = 20.72;

// A piece of ray spans about one scale height of altitude at the rate the ray rises
// or sinks where the piece starts; rays nearer level than this take pieces of 50
// scale heights.
constexpr double kLevel = 0.02;

// The parameter interval of the ray o + t d inside the box (empty: lo >= hi).
void slab(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi, double* t0,
          double* t1) {
  double a = -kInfinity, b = kInfinity;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (o[i] < lo[i] || o[i] > hi[i]) a = kInfinity;
      continue;
    }
    const double u = (lo[i] - o[i]) / d[i], v = (hi[i] - o[i]) / d[i];
    a = std::max(a, std::min(u, v));
    b = std::min(b, std::max(u, v));
  }
  *t0 = std::max(a, 0.0);
  *t1 = b;
}

// The distances along o + t d (d unit) to the sphere of `radius` about `center`:
// the near and far roots, from the centre's distance to the line (no cancellation
// for a ray at the surface of a sphere of 6360 km). False when the line misses it.
bool sphereRoots(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& center, double radius, double* tNear,
                 double* tFar) {
  const glm::dvec3 oc = o - center;
  const double b = glm::dot(oc, d);
  const glm::dvec3 closest = oc - b * d;
  const double disc = (radius - glm::length(closest)) * (radius + glm::length(closest));
  if (disc < 0.0) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  const double c = glm::dot(oc, oc) - radius * radius;
  const double r0 = q, r1 = q != 0.0 ? c / q : 0.0;
  *tNear = std::min(r0, r1);
  *tFar = std::max(r0, r1);
  return true;
}

}  // namespace

// One ray being tracked: where it starts, its direction, its channel and where it ends.
struct Media::Walk {
  glm::dvec3 o, d;
  int channel;
  double end;
};

std::optional<Media> Media::of(const FogDesc& fog, const AtmosphereDesc& atmosphere,
                               const std::vector<MediumDesc>& boxes) {
  Media m;
  const bool fogMedium = fog.enabled && fog.model == FogModel::Volumetric;
  if (fogMedium) {
    const double falloff = fog.heightFalloff;
    m.fog_ = Fog{fog.scattering, fog.scattering + fog.absorption, fog.anisotropy, falloff,
                 falloff > 0.0 ? kFogCeilingDepth / falloff : kInfinity};
  }
  if (atmosphere.enabled) {
    const double r = atmosphere.planetRadius;
    m.air_ = Air{atmospheretext::atmosphereOf(atmosphere), r, r + atmosphere.thickness, glm::dvec3(0.0, -r, 0.0),
                 atmosphere.groundAlbedo};
  }
  for (const MediumDesc& b : boxes) m.boxes_.push_back(Box{b.min, b.max, b.scattering, b.scattering + b.absorption, b.anisotropy});
  if (!m.fog_ && !m.air_ && m.boxes_.empty()) return std::nullopt;
  if (fogMedium && fog.heightFalloff == 0.0f && !m.air_ && m.boxes_.empty()) m.homogeneous_ = Medium::of(fog);
  return m;
}

double Media::altitude(const glm::dvec3& p) const { return glm::length(p - air_->center) - air_->bottom; }

template <typename F>
void Media::eachScatterer(const glm::dvec3& p, int c, F&& f) const {
  if (fog_) {
    const double factor = fog_->falloff > 0.0 ? (p.y < fog_->ceiling ? std::exp(-fog_->falloff * p.y) : 0.0) : 1.0;
    if (f(float(fog_->extinction[c] * factor), float(fog_->scattering[c] * factor), Phase{fog_->g, false})) return;
  }
  for (const Box& b : boxes_) {
    if (glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max))) {
      if (f(b.extinction[c], b.scattering[c], Phase{b.g, false})) return;
    }
  }
  if (air_ && glm::length(p - air_->center) < air_->top) {
    const atmospheretext::Atmosphere& a = air_->text;
    const glm::vec3 density = atmospheretext::atmosphereDensities(a, float(altitude(p)));
    const glm::vec3 extinction = atmospheretext::atmosphereExtinction(a, density);
    // Rayleigh's extinction is its scattering; Mie's and ozone's absorption go with Mie.
    const float rayleigh = a.rayleighScattering[c] * density.x;
    if (f(rayleigh, rayleigh, Phase{0.0f, true})) return;
    f(extinction[c] - rayleigh, a.mieScattering[c] * density.y, Phase{a.mieAnisotropy, false});
  }
}

float Media::airAt(const glm::dvec3& p, int channel) const {
  if (glm::length(p - air_->center) >= air_->top) return 0.0f;
  const atmospheretext::Atmosphere& a = air_->text;
  return atmospheretext::atmosphereExtinction(a, atmospheretext::atmosphereDensities(a, float(altitude(p))))[channel];
}

Media::Coefficients Media::at(const glm::dvec3& p, int channel) const {
  Coefficients sum;
  eachScatterer(p, channel, [&](float extinction, float scattering, Phase) {
    sum.extinction += extinction;
    sum.scattering += scattering;
    return false;
  });
  return sum;
}

Phase Media::phaseAt(const glm::dvec3& p, int channel, float u) const {
  float left = u * at(p, channel).scattering;
  Phase chosen;
  eachScatterer(p, channel, [&](float, float scattering, Phase phase) {
    if (scattering > 0.0f) chosen = phase;
    left -= scattering;
    return left < 0.0f;
  });
  return chosen;
}

std::optional<double> Media::groundHit(const glm::dvec3& o, const glm::dvec3& d) const {
  if (!air_) return std::nullopt;
  double tNear = 0.0, tFar = 0.0;
  // From inside the planet (a valley under y = 0) the scene's own ground is the ground.
  if (glm::length(o - air_->center) < air_->bottom) return std::nullopt;
  if (!sphereRoots(o, d, air_->center, air_->bottom, &tNear, &tFar) || !(tNear > 0.0)) return std::nullopt;
  return tNear;
}

// Where tracking along o + t d ends: maxDistance or the ground, whichever is nearer.
double Media::end(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, bool* ground) const {
  const std::optional<double> g = groundHit(o, d);
  *ground = g && *g < maxDistance;
  return *ground ? *g : maxDistance;
}

double Media::pieceEnd(double t, const Walk& w) const {
  double end = w.end;
  for (const Box& b : boxes_) {
    double t0 = 0.0, t1 = 0.0;
    slab(w.o, w.d, b.min, b.max, &t0, &t1);
    if (t0 >= t1) continue;
    if (t0 > t) {
      end = std::min(end, t0);
    } else if (t1 > t) {
      end = std::min(end, t1);
    }
  }
  const glm::dvec3 p = w.o + t * w.d;
  double scale = kInfinity, rise = 0.0;
  if (fog_ && fog_->falloff > 0.0) {
    if (w.d.y != 0.0) {
      const double ceiling = (fog_->ceiling - w.o.y) / w.d.y;
      if (ceiling > t) end = std::min(end, ceiling);
    }
    // Above its ceiling the fog is not there: no pace to keep.
    if (p.y < fog_->ceiling) {
      scale = 1.0 / fog_->falloff;
      rise = std::abs(w.d.y);
    }
  }
  if (air_) {
    // The top of the air is a boundary; beyond it the air is not there.
    double tNear = 0.0, tFar = 0.0;
    if (sphereRoots(w.o, w.d, air_->center, air_->top, &tNear, &tFar)) {
      if (tNear > t) {
        end = std::min(end, tNear);
      } else if (tFar > t) {
        end = std::min(end, tFar);
      }
    }
    const atmospheretext::Atmosphere& a = air_->text;
    // The layer that holds most of this channel's extinction sets the pace.
    const double air = a.rayleighScattering[w.channel] >= a.mieScattering[w.channel] + a.mieAbsorption[w.channel]
                           ? a.rayleighScaleHeight
                           : a.mieScaleHeight;
    if (glm::length(p - air_->center) < air_->top && air < scale) {
      scale = air;
      rise = std::abs(glm::dot(w.d, glm::normalize(p - air_->center)));
    }
  }
  if (scale < kInfinity) end = std::min(end, t + scale / std::max(rise, kLevel));
  return end;
}

double Media::majorant(double t0, double t1, const Walk& w) const {
  const int c = w.channel;
  double sum = 0.0;
  if (fog_) {
    if (fog_->falloff == 0.0) {
      sum += fog_->extinction[c];
    } else {
      const double lowest = std::min(w.o.y + t0 * w.d.y, w.o.y + t1 * w.d.y);
      if (lowest < fog_->ceiling) sum += fog_->extinction[c] * std::exp(-fog_->falloff * lowest);
    }
  }
  for (const Box& b : boxes_) {
    double s0 = 0.0, s1 = 0.0;
    slab(w.o, w.d, b.min, b.max, &s0, &s1);
    if (s0 < s1 && s0 < t1 && s1 > t0) sum += b.extinction[c];
  }
  if (air_) {
    const glm::dvec3 oc = w.o - air_->center;
    const double closest = std::clamp(-glm::dot(oc, w.d), t0, t1);
    const double lo = glm::length(oc + closest * w.d) - air_->bottom;
    // A piece lies wholly inside the air or wholly outside it (pieceEnd).
    if (lo < air_->top - air_->bottom) {
      const double hi = t1 < kInfinity ? std::max(glm::length(oc + t0 * w.d), glm::length(oc + t1 * w.d)) - air_->bottom
                                       : kInfinity;
      const atmospheretext::Atmosphere& a = air_->text;
      const glm::vec3 bound = atmospheretext::atmosphereDensityBound(a, float(lo), float(std::min(hi, 1e30)));
      // float(lo) rounds; a bound a hair higher cannot fall short of the densities.
      sum += double(atmospheretext::atmosphereExtinction(a, bound)[c]) * (1.0 + 1e-5);
    }
  }
  return sum;
}

Media::Flight Media::track(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, int channel,
                           Pcg32& rng) const {
  Flight f;
  bool ground = false;
  const Walk w{o, d, channel, end(o, d, maxDistance, &ground)};
  double t = 0.0;
  while (t < w.end) {
    const double pieceEnd = this->pieceEnd(t, w);
    const double bound = majorant(t, pieceEnd, w);
    while (bound > 0.0) {
      const double next = t - std::log1p(-double(rng.uniform())) / bound;
      if (next >= pieceEnd) break;
      t = next;
      const glm::dvec3 p = o + t * d;
      const Coefficients k = at(p, channel);
      if (double(rng.uniform()) * bound >= double(k.extinction)) continue;  // a null collision
      f.distance = t;
      if (!(k.scattering > 0.0f)) {
        f.event = Event::Absorbed;
        f.weight = 0.0f;
        return f;
      }
      f.event = Event::Scattered;
      f.weight = k.scattering / k.extinction;
      f.phase = phaseAt(p, channel, rng.uniform());
      return f;
    }
    t = pieceEnd;
  }
  f.distance = w.end;
  if (ground) {
    f.event = Event::Ground;
    f.groundNormal = glm::normalize(o + w.end * d - air_->center);
  }
  return f;
}

// The optical depth of the fog and the boxes over [0, length] of o + t d in
// `channel`, in closed form: a homogeneous fog's sigma length, a height fog's
// integral of exp(-falloff y) up to its ceiling, each box's sigma times its chord.
double Media::closedFormDepth(const glm::dvec3& o, const glm::dvec3& d, double length, int c) const {
  double depth = 0.0;
  if (fog_ && fog_->falloff == 0.0) depth += double(fog_->extinction[c]) * length;
  if (fog_ && fog_->falloff > 0.0) {
    // Where the ray is below the ceiling: [a, b].
    double a = 0.0, b = length;
    if (d.y != 0.0) {
      const double crossing = (fog_->ceiling - o.y) / d.y;
      if (d.y > 0.0) b = std::min(b, crossing);
      if (d.y < 0.0) a = std::max(a, crossing);
    } else if (o.y >= fog_->ceiling) {
      b = a;
    }
    if (b > a) {
      // sigma exp(-k y(a)) (1 - exp(-k dy (b - a))) / (k dy), its limit (b - a) where
      // dy -> 0: expm1 keeps it exact for nearly level rays.
      const double k = fog_->falloff, x = k * d.y * (b - a);
      const double start = double(fog_->extinction[c]) * std::exp(-k * (o.y + a * d.y));
      depth += start * (b - a) * (x != 0.0 ? -std::expm1(-x) / x : 1.0);
    }
  }
  for (const Box& box : boxes_) {
    double t0 = 0.0, t1 = 0.0;
    slab(o, d, box.min, box.max, &t0, &t1);
    t1 = std::min(t1, length);
    if (t1 > t0) depth += double(box.extinction[c]) * (t1 - t0);
  }
  return depth;
}

// The air's part, by residual ratio tracking (Novak et al. 2014): along each piece,
// the least density the piece can hold is taken in closed form, and only the rest,
// between that and the most, is tracked.
double Media::airTransmittance(const glm::dvec3& o, const glm::dvec3& d, double length, int channel, Pcg32& rng) const {
  const Walk w{o, d, channel, length};
  const glm::dvec3 oc = o - air_->center;
  const atmospheretext::Atmosphere& a = air_->text;
  double t = 0.0, through = 1.0;
  while (t < length) {
    const double pieceEnd = std::min(this->pieceEnd(t, w), length);
    const double lo = glm::length(oc + std::clamp(-glm::dot(oc, d), t, pieceEnd) * d) - air_->bottom;
    if (lo < air_->top - air_->bottom) {
      const double hi = std::max(glm::length(oc + t * d), glm::length(oc + pieceEnd * d)) - air_->bottom;
      const double most = double(atmospheretext::atmosphereExtinction(
                              a, atmospheretext::atmosphereDensityBound(a, float(lo), float(hi)))[channel]) *
                          (1.0 + 1e-5);
      const double least = double(atmospheretext::atmosphereExtinction(
                               a, atmospheretext::atmosphereDensityFloor(a, float(lo), float(hi)))[channel]) *
                           (1.0 - 1e-5);
      through *= std::exp(-least * (pieceEnd - t));
      const double rate = most - least;
      for (double s = t; rate > 0.0;) {
        s -= std::log1p(-double(rng.uniform())) / rate;
        if (s >= pieceEnd) break;
        through *= 1.0 - (double(airAt(o + s * d, channel)) - least) / rate;
      }
    }
    t = pieceEnd;
  }
  return through;
}

float Media::transmittance(const glm::dvec3& o, const glm::dvec3& d, double distance, int channel, Pcg32& rng) const {
  bool ground = false;
  const double length = end(o, d, distance, &ground);
  if (ground) return 0.0f;
  double through = std::exp(-closedFormDepth(o, d, length, channel));
  if (air_ && through > 0.0) through *= airTransmittance(o, d, length, channel, rng);
  return float(through);
}

}  // namespace engine::rt
