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
// or sinks where the piece starts; rays nearer level than this take pieces of 20
// scale heights (a level ray's altitude grows by another half of one in them).
constexpr double kLevel = 0.05;

// Gauss-Legendre's four nodes on [-1, 1] (the positive half) and their weights:
// exact for polynomials of degree 7. Over a piece a scale height of altitude long
// that is within 1.4e-7 of adaptive quadratures (Media.TransmittanceIsTheQuadratures,
// float densities), as eight nodes were, at half the cost.
constexpr double kNodes[2] = {0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[2] = {0.6521451548625461, 0.3478548451374538};

double mean(const glm::dvec3& v) { return (v.x + v.y + v.z) / 3.0; }
// Infinite optical depth in the channels a tail of fog extinguishes.
void addTail(glm::dvec3& tau, const glm::dvec3& rate) {
  for (int k = 0; k < 3; ++k) tau[k] = rate[k] > 0.0 ? kInfinity : tau[k];
}
double largest(const glm::vec3& v) { return double(std::max({v.x, v.y, v.z})); }

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
void Media::eachMedium(const glm::dvec3& p, F&& f) const {
  if (fog_) {
    const float factor =
        fog_->falloff > 0.0 ? (p.y < fog_->ceiling ? float(std::exp(-fog_->falloff * p.y)) : 0.0f) : 1.0f;
    f(fog_->extinction * factor, fog_->scattering * factor, Phase{fog_->g, false});
  }
  for (const Box& b : boxes_) {
    if (glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max))) {
      f(b.extinction, b.scattering, Phase{b.g, false});
    }
  }
  if (air_ && glm::length(p - air_->center) < air_->top) {
    const atmospheretext::Atmosphere& a = air_->text;
    const glm::vec3 density = atmospheretext::atmosphereDensities(a, float(altitude(p)));
    const glm::vec3 extinction = atmospheretext::atmosphereExtinction(a, density);
    // Rayleigh's extinction is its scattering; Mie's and ozone's absorption go with Mie.
    const glm::vec3 rayleigh = a.rayleighScattering * density.x;
    f(rayleigh, rayleigh, Phase{0.0f, true});
    f(extinction - rayleigh, a.mieScattering * density.y, Phase{a.mieAnisotropy, false});
  }
}

Media::Coefficients Media::at(const glm::dvec3& p) const {
  Coefficients sum;
  eachMedium(p, [&](const glm::vec3& extinction, const glm::vec3& scattering, Phase) {
    sum.extinction += extinction;
    sum.scattering += scattering;
  });
  return sum;
}

glm::vec3 Media::airExtinction(const glm::dvec3& p) const {
  if (glm::length(p - air_->center) >= air_->top) return glm::vec3(0.0f);
  const atmospheretext::Atmosphere& a = air_->text;
  return atmospheretext::atmosphereExtinction(a, atmospheretext::atmosphereDensities(a, float(altitude(p))));
}

// The medium that scatters at p, drawn by u in proportion to the media's scattering
// (their channels' mean); its scattering over the chance of drawing it.
Phase Media::phaseAt(const glm::dvec3& p, float u, glm::vec3* scattering) const {
  const Coefficients all = at(p);
  const float total = (all.scattering.x + all.scattering.y + all.scattering.z) / 3.0f;
  float left = u * total;
  Phase chosen;
  *scattering = glm::vec3(0.0f);
  bool done = false;
  eachMedium(p, [&](const glm::vec3&, const glm::vec3& s, Phase phase) {
    const float share = (s.x + s.y + s.z) / 3.0f;
    if (done || !(share > 0.0f)) return;
    chosen = phase;
    *scattering = s * (total / share);
    left -= share;
    done = left < 0.0f;
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

// Where a ray along o + t d ends: maxDistance or the ground, whichever is nearer.
double Media::end(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, bool* ground) const {
  const std::optional<double> g = groundHit(o, d);
  *ground = g && *g < maxDistance;
  return *ground ? *g : maxDistance;
}

// The end of the piece of the line from t on (at most `end`) over which every
// medium's extinction is smooth: boxes' faces, a height fog's ceiling, the air's top
// and the ozone tent's kinks bound it; a height fog and the air pace it (a scale
// height of altitude, at the rate the ray rises there). Infinity where nothing does:
// only a homogeneous fog lies ahead.
Media::Line Media::lineOf(const glm::dvec3& o, const glm::dvec3& d) const {
  Line line{o, d, {}, 0};
  if (fog_ && fog_->falloff > 0.0 && d.y != 0.0) line.cuts[line.count++] = (fog_->ceiling - o.y) / d.y;
  if (air_) {
    const atmospheretext::Atmosphere& a = air_->text;
    const double ozone = air_->bottom + double(a.ozoneCenter);
    for (double radius : {air_->top, ozone - a.ozoneHalfWidth, ozone, ozone + a.ozoneHalfWidth}) {
      double tNear = 0.0, tFar = 0.0;
      if (radius > air_->bottom && sphereRoots(o, d, air_->center, radius, &tNear, &tFar)) {
        line.cuts[line.count++] = tNear;
        line.cuts[line.count++] = tFar;
      }
    }
  }
  return line;
}

double Media::pieceEnd(const Line& line, double t, double end) const {
  const glm::dvec3 &o = line.o, &d = line.d;
  const auto boundary = [&](double at) {
    if (at > t) end = std::min(end, at);
  };
  for (int i = 0; i < line.count; ++i) boundary(line.cuts[i]);
  for (const Box& b : boxes_) {
    double t0 = 0.0, t1 = 0.0;
    slab(o, d, b.min, b.max, &t0, &t1);
    if (t0 < t1) boundary(t0), boundary(t1);
  }
  const glm::dvec3 p = o + t * d;
  double scale = kInfinity, rise = 0.0;
  if (fog_ && fog_->falloff > 0.0 && p.y < fog_->ceiling) scale = 1.0 / fog_->falloff, rise = std::abs(d.y);
  if (air_) {
    const atmospheretext::Atmosphere& a = air_->text;
    const double h = altitude(p);
    if (h < air_->top - air_->bottom) {
      // Mie's pace while its extinction is at least a hundredth of Rayleigh's there.
      const double mie = std::exp(-h / a.mieScaleHeight) * largest(a.mieScattering + a.mieAbsorption);
      const double rayleigh = std::exp(-h / a.rayleighScaleHeight) * largest(a.rayleighScattering);
      const double air = mie > 0.01 * rayleigh ? std::min(a.mieScaleHeight, a.rayleighScaleHeight) : a.rayleighScaleHeight;
      if (air < scale) scale = air, rise = std::abs(glm::dot(d, glm::normalize(p - air_->center)));
    }
  }
  if (scale < kInfinity) end = std::min(end, t + scale / std::max(rise, kLevel));
  return end;
}

// The fog's and the boxes' optical depth over [a, b] of o + t d, in closed form: a
// homogeneous fog's sigma (b - a), a height fog's integral of exp(-falloff y) below
// its ceiling, each box's sigma times its chord.
glm::dvec3 Media::closedFormDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const {
  glm::dvec3 depth(0.0);
  if (fog_ && fog_->falloff == 0.0) depth += glm::dvec3(fog_->extinction) * (b - a);
  if (fog_ && fog_->falloff > 0.0) {
    double lo = a, hi = b;  // below the ceiling
    if (d.y != 0.0) {
      const double crossing = (fog_->ceiling - o.y) / d.y;
      if (d.y > 0.0) hi = std::min(hi, crossing);
      if (d.y < 0.0) lo = std::max(lo, crossing);
    } else if (o.y >= fog_->ceiling) {
      hi = lo;
    }
    if (hi > lo) {
      // sigma exp(-k y(lo)) (1 - exp(-k dy (hi - lo))) / (k dy), its limit (hi - lo)
      // where dy -> 0: expm1 keeps it exact for nearly level rays.
      const double k = fog_->falloff, x = k * d.y * (hi - lo);
      depth += glm::dvec3(fog_->extinction) * (std::exp(-k * (o.y + lo * d.y)) * (hi - lo) *
                                               (x != 0.0 ? -std::expm1(-x) / x : 1.0));
    }
  }
  for (const Box& box : boxes_) {
    double t0 = 0.0, t1 = 0.0;
    slab(o, d, box.min, box.max, &t0, &t1);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t1 > t0) depth += glm::dvec3(box.extinction) * (t1 - t0);
  }
  return depth;
}

// The air's optical depth over [a, b], within one piece: Gauss-Legendre.
glm::dvec3 Media::airDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const {
  if (!air_ || !(b > a)) return glm::dvec3(0.0);
  const double half = 0.5 * (b - a), middle = 0.5 * (a + b);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < 2; ++i) {
    sum += kWeights[i] * (glm::dvec3(airExtinction(o + (middle - half * kNodes[i]) * d)) +
                          glm::dvec3(airExtinction(o + (middle + half * kNodes[i]) * d)));
  }
  return sum * half;
}

// The optical depth over [a, b] within one piece: the closed forms and the air's.
glm::dvec3 Media::pieceDepth(const glm::dvec3& o, const glm::dvec3& d, double a, double b) const {
  return closedFormDepth(o, d, a, b) + airDepth(o, d, a, b);
}

// What extinguishes light past the last piece, for ever: a homogeneous fog's, if any.
glm::dvec3 Media::tailRate() const {
  return fog_ && fog_->falloff == 0.0 ? glm::dvec3(fog_->extinction) : glm::dvec3(0.0);
}

// Where in [a, b], one piece, the optical depth of `channel` from a reaches `depth`
// (less than the piece's): Newton's steps on it, kept within a shrinking bracket.
double Media::solve(const glm::dvec3& o, const glm::dvec3& d, double a, double b, int c, double depth) const {
  double lo = a, hi = b;
  const double whole = pieceDepth(o, d, a, b)[c];
  double s = a + (b - a) * std::clamp(depth / whole, 0.0, 1.0);
  for (int i = 0; i < 40; ++i) {
    const double f = pieceDepth(o, d, a, s)[c] - depth;
    if (std::abs(f) <= 1e-12 * depth) break;
    (f > 0.0 ? hi : lo) = s;
    if (hi - lo <= 1e-13 * std::max(1.0, std::abs(s))) break;
    const double sigma = double(at(o + s * d).extinction[c]);
    double next = sigma > 0.0 ? s - f / sigma : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    s = next;
  }
  return s;
}

Media::Flight Media::fly(const glm::dvec3& o, const glm::dvec3& d, double maxDistance, float uChannel, float u,
                         float uPhase) const {
  Flight f;
  bool ground = false;
  const double e = end(o, d, maxDistance, &ground);
  const int c = std::min(2, int(uChannel * 3.0f));
  const double target = -std::log1p(-double(u));
  glm::dvec3 tau(0.0);
  double t = 0.0;
  bool collided = false;
  const Line line = lineOf(o, d);
  while (t < e && !collided) {
    const double next = pieceEnd(line, t, e);
    if (next == kInfinity) {
      // Only a homogeneous fog lies ahead, for ever.
      const glm::dvec3 rate = tailRate();
      if (rate[c] > 0.0) {
        const double s = t + (target - tau[c]) / rate[c];
        tau += rate * (s - t), t = s, collided = true;
      } else {
        addTail(tau, rate);
        t = kInfinity;
      }
      break;
    }
    const glm::dvec3 piece = pieceDepth(o, d, t, next);
    if (tau[c] + piece[c] >= target) {
      const double s = solve(o, d, t, next, c, target - tau[c]);
      tau += pieceDepth(o, d, t, s);
      t = s, collided = true;
    } else {
      tau += piece, t = next;
    }
  }
  const glm::dvec3 tr = glm::exp(-tau);
  if (!collided) {
    f.distance = e;
    f.weight = mean(tr) > 0.0 ? glm::vec3(tr / mean(tr)) : glm::vec3(0.0f);
    if (ground) {
      f.event = Event::Ground;
      f.groundNormal = glm::normalize(o + e * d - air_->center);
    }
    return f;
  }
  const glm::dvec3 p = o + t * d;
  glm::vec3 scattering(0.0f);
  f.event = Event::Scattered;
  f.distance = t;
  f.phase = phaseAt(p, uPhase, &scattering);
  const double density = mean(glm::dvec3(at(p).extinction) * tr);
  f.weight = density > 0.0 ? glm::vec3(glm::dvec3(scattering) * tr / density) : glm::vec3(0.0f);
  return f;
}

glm::vec3 Media::transmittance(const glm::dvec3& o, const glm::dvec3& d, double distance) const {
  if (homogeneous_) return homogeneous_->transmittance(distance);
  bool ground = false;
  const double e = end(o, d, distance, &ground);
  if (ground) return glm::vec3(0.0f);
  double finite = 0.0;
  glm::dvec3 tau(0.0);
  const Line line = lineOf(o, d);
  for (double t = 0.0; t < e;) {
    const double next = pieceEnd(line, t, e);
    if (next == kInfinity) {
      addTail(tau, tailRate());
      break;
    }
    tau += airDepth(o, d, t, next);
    finite = t = next;
  }
  return glm::vec3(glm::exp(-(tau + closedFormDepth(o, d, 0.0, finite))));
}

}  // namespace engine::rt
