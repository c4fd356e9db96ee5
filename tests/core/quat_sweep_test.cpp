// Slerp, nlerp and the CUBICSPLINE rotation path swept over millions of random unit
// quaternions against double-precision references: identical keys, keys 1 ulp apart
// (renormalised or not), generic, close, opposite and near-opposite pairs, with t = 0
// and t = 1 exactly among the random t. Then the issue's key, whose own float dot
// rounds to 1 - 2^-23 once normalised, and thousands of its neighbours whose dot
// rounds to 1 -/+ 2^-23: slerp(k, k, t) once came back as identity for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <utility>

#include "anim/clip.h"
#include "core/math.h"

namespace engine {
namespace {

// Bounds against the double reference. Each component of a float result is a short
// sum of products of values <= 1, each rounded by at most half an ulp (6e-8), and
// normalisation rounds once more: a few 1e-7 in the 4D direction, which the rotation
// angle doubles. 1e-6 rad is about 8 float epsilons (2^-23) of rotation angle; the
// worst seen is 3.0e-7 for slerp, 2.3e-7 for nlerp and 5.4e-7 for the Hermite
// (generic keys, whose curve dips towards 0.7 in length). A 0/0 or a snap to identity
// is off by the whole angle between the keys and identity.
constexpr double kAngleBound = 1e-6;
// |result| - 1: one float normalisation leaves about 1.5 ulps (1.7e-7 seen).
constexpr double kLengthBound = 1e-6;
constexpr int kPairsPerKind = 300000;
constexpr int kHermitePairsPerKind = 100000;

using DQuat = glm::dvec4;  // w, x, y, z in double

DQuat toDouble(const glm::quat& q) { return {q.w, q.x, q.y, q.z}; }
DQuat unit(const DQuat& q) { return q / glm::length(q); }

// Rotation angle between two unit quaternions, either sign: atan2 keeps tiny angles
// exact where acos of a dot near 1 does not.
double angleBetween(const DQuat& p, DQuat q) {
  if (glm::dot(p, q) < 0.0) q = -q;
  return 4.0 * std::atan2(glm::length(p - q), glm::length(p + q));
}

// Slerp of the normalised keys, along b as given (the caller picks the hemisphere).
DQuat refSlerp(DQuat a, DQuat b, double t) {
  a = unit(a);
  b = unit(b);
  double theta = 2.0 * std::atan2(glm::length(a - b), glm::length(a + b));
  if (theta == 0.0) return a;
  double s = std::sin(theta);
  return unit(a * (std::sin((1.0 - t) * theta) / s) + b * (std::sin(t * theta) / s));
}

// Nlerp of the keys as given (float nlerp does not normalise its inputs either).
DQuat refNlerp(const DQuat& a, const DQuat& b, double t) { return unit(a * (1.0 - t) + b * t); }

// The glTF Hermite with zero tangents between two keys, normalised.
DQuat refHermite(const DQuat& a, const DQuat& b, double t) {
  double s2 = t * t, s3 = s2 * t;
  return unit(a * (2 * s3 - 3 * s2 + 1) + b * (-2 * s3 + 3 * s2));
}

// Shoemake's uniform random rotation, rounded to float.
glm::quat randomUnit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double u1 = u(rng), a = 2.0 * std::numbers::pi * u(rng), b = 2.0 * std::numbers::pi * u(rng);
  double r0 = std::sqrt(1.0 - u1), r1 = std::sqrt(u1);
  return glm::quat(static_cast<float>(r0 * std::sin(a)), static_cast<float>(r0 * std::cos(a)),
                   static_cast<float>(r1 * std::sin(b)), static_cast<float>(r1 * std::cos(b)));
}

float ulpStep(float x, int steps) {
  float to = steps > 0 ? INFINITY : -INFINITY;
  for (int i = 0; i < std::abs(steps); ++i) x = std::nextafter(x, to);
  return x;
}

// Every component moved by `steps` ulps, each in a random direction.
glm::quat perturb(glm::quat q, std::mt19937_64& rng, int maxSteps) {
  std::uniform_int_distribution<int> step(-maxSteps, maxSteps);
  for (int c = 0; c < 4; ++c) q[c] = ulpStep(q[c], maxSteps == 1 ? (rng() & 1 ? 1 : -1) : step(rng));
  return q;
}

// b = a turned by an angle spread log-uniformly over 1e-7..1 rad: both sides of
// kSlerpNlerpBelow.
glm::quat nearby(const glm::quat& a, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-7.0, 0.0);
  glm::quat axis = randomUnit(rng);
  float angle = static_cast<float>(std::pow(10.0, u(rng)));
  return a * glm::angleAxis(angle, glm::normalize(glm::vec3(axis.x, axis.y, axis.z)));
}

enum class Kind { Identical, OneUlpRenormalised, OneUlpRaw, Generic, Close, Opposite, NearOpposite };
constexpr Kind kKinds[] = {Kind::Identical, Kind::OneUlpRenormalised, Kind::OneUlpRaw, Kind::Generic,
                           Kind::Close,     Kind::Opposite,           Kind::NearOpposite};

const char* name(Kind k) {
  switch (k) {
    case Kind::Identical: return "identical";
    case Kind::OneUlpRenormalised: return "1 ulp, renormalised";
    case Kind::OneUlpRaw: return "1 ulp, raw";
    case Kind::Generic: return "generic";
    case Kind::Close: return "close";
    case Kind::Opposite: return "opposite";
    case Kind::NearOpposite: return "near-opposite";
  }
  return "";
}

std::pair<glm::quat, glm::quat> makePair(Kind kind, std::mt19937_64& rng) {
  glm::quat a = randomUnit(rng);
  switch (kind) {
    case Kind::Identical: return {a, a};
    case Kind::OneUlpRenormalised: return {a, glm::normalize(perturb(a, rng, 1))};
    case Kind::OneUlpRaw: return {a, perturb(a, rng, 1)};
    case Kind::Generic: return {a, randomUnit(rng)};
    case Kind::Close: return {a, nearby(a, rng)};
    case Kind::Opposite: return {a, -a};
    case Kind::NearOpposite: return {a, -(rng() & 1 ? perturb(a, rng, 1) : nearby(a, rng))};
  }
  return {a, a};
}

// One t in eight is 0 and one is 1 exactly.
float randomT(std::mt19937_64& rng, int i) {
  if (i % 8 == 0) return 0.0f;
  if (i % 8 == 1) return 1.0f;
  return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
}

struct Worst {
  double angle = 0.0;
  double length = 0.0;
  int failures = 0;
  std::string example;
};

// Error of r against the reference ref(b) on the side of a. Where a and b are
// within 1e-6 of perpendicular both arcs are equally short and float and double
// may pick different ones; either is right there.
template <class Ref>
void check(Worst& w, const glm::quat& r, const glm::quat& a, const glm::quat& b, float t, Ref ref) {
  DQuat da = toDouble(a), db = toDouble(b);
  double d = glm::dot(unit(da), unit(db));
  double err = angleBetween(unit(toDouble(r)), ref(da, d < 0.0 ? -db : db, t));
  if (std::abs(d) < 1e-6)
    err = std::min(err, angleBetween(unit(toDouble(r)), ref(da, d < 0.0 ? db : -db, t)));
  double len = std::abs(glm::length(toDouble(r)) - 1.0);
  if (!(err <= w.angle)) w.angle = err;  // NaN sticks
  if (!(len <= w.length)) w.length = len;
  if (!(err <= kAngleBound && len <= kLengthBound) && w.failures++ == 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "a=(%.9g %.9g %.9g %.9g) b=(%.9g %.9g %.9g %.9g) (w x y z) t=%.9g: "
                  "error %g rad, |r|-1 %g", a.w, a.x, a.y, a.z, b.w, b.x, b.y, b.z, t, err, len);
    w.example = buf;
  }
}

void report(const char* what, Kind kind, const Worst& w) {
  std::printf("  %-8s %-20s worst angle error %.3g rad, worst |len - 1| %.3g\n", what, name(kind), w.angle,
              w.length);
  EXPECT_EQ(w.failures, 0) << what << ", " << name(kind) << ": first failure " << w.example;
}

// Every kind of pair through `interpolate`, against the double-precision `reference`.
template <typename Interpolate, typename Reference>
void sweep(const char* what, std::uint64_t seed, Interpolate interpolate, Reference reference) {
  std::mt19937_64 rng(seed);
  for (Kind kind : kKinds) {
    Worst w;
    for (int i = 0; i < kPairsPerKind; ++i) {
      auto [a, b] = makePair(kind, rng);
      float t = randomT(rng, i);
      check(w, interpolate(a, b, t), a, b, t, reference);
    }
    report(what, kind, w);
  }
}

TEST(QuatSweep, SlerpIsUnitAndMatchesTheDoubleSlerp) {
  sweep("slerp", 20240611, [](const glm::quat& a, const glm::quat& b, float t) { return slerp(a, b, t); }, refSlerp);
}

TEST(QuatSweep, NlerpIsUnitAndMatchesTheDoubleNlerp) {
  sweep("nlerp", 7, [](const glm::quat& a, const glm::quat& b, float t) { return nlerp(a, b, t); }, refNlerp);
}

// Two CUBICSPLINE rotation keys at times 0 and 1 with zero tangents; values are set
// per sample so that one Track serves the whole sweep.
Track cubicTrack() {
  Track t;
  t.joint = 0;
  t.path = AnimPath::Rotation;
  t.interpolation = Interpolation::CubicSpline;
  t.times = {0.0f, 1.0f};
  t.values.assign(6, glm::vec4(0.0f));
  return t;
}

glm::vec4 xyzw(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

void setKeys(Track& track, const glm::quat& a, const glm::quat& b) {
  track.values[1] = xyzw(a);
  track.values[4] = xyzw(b);
}

TEST(QuatSweep, CubicSplineRotationIsUnitAndMatchesTheDoubleHermite) {
  std::mt19937_64 rng(99);
  Track track = cubicTrack();
  for (Kind kind : kKinds) {
    Worst w;
    for (int i = 0; i < kHermitePairsPerKind; ++i) {
      auto [a, b] = makePair(kind, rng);
      float t = randomT(rng, i);
      setKeys(track, a, b);
      check(w, sampleQuat(track, t), a, b, t, refHermite);
    }
    report("hermite", kind, w);
  }
}

// The issue's key: a joint with 1309 constant rotation keys drawn un-rotated. Read
// both ways, x y z w as glTF stores it and w x y z.
const glm::quat kIssueKeys[] = {glm::quat(-0.4288765f, 0.9033632f, -7.474e-8f, -1.0567e-7f),
                                glm::quat(0.9033632f, -7.474e-8f, -1.0567e-7f, -0.4288765f)};

float maxDiff(const glm::quat& p, const glm::quat& q) {
  float m = 0.0f;
  for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(p[c] - q[c]));
  return m;
}

// slerp, nlerp and the zero-tangent Hermite of (k, k) must give k back for any t.
void expectHoldsKey(const glm::quat& k, Track& cubic) {
  setKeys(cubic, k, k);
  for (int i = 0; i <= 64; ++i) {
    float t = i / 64.0f;
    ASSERT_LE(maxDiff(slerp(k, k, t), k), 1e-6f) << "slerp t=" << t << " k.w=" << k.w;
    ASSERT_LE(maxDiff(nlerp(k, k, t), k), 1e-6f) << "nlerp t=" << t << " k.w=" << k.w;
    ASSERT_LE(maxDiff(sampleQuat(cubic, t), k), 1e-6f) << "hermite t=" << t << " k.w=" << k.w;
  }
}

TEST(QuatRegression, IssueKeyInterpolatesToItself) {
  Track cubic = cubicTrack();
  for (const glm::quat& raw : kIssueKeys) {
    glm::quat k = safeNormalize(raw);  // what Clip::build stores
    EXPECT_EQ(glm::dot(k, k), 1.0f - 0x1p-23f);  // the rounding that skipped the old nlerp branch
    expectHoldsKey(raw, cubic);
    expectHoldsKey(k, cubic);
  }
}

TEST(QuatRegression, ConstantTrackOf1309KeysHoldsTheKey) {
  RawSkeleton skeleton;
  skeleton.parents = {-1};
  skeleton.restPose = {Srt{}};
  Skeleton s = Skeleton::build(skeleton).value();
  for (const glm::quat& raw : kIssueKeys) {
    RawClip clip;
    Track linear{0, AnimPath::Rotation, Interpolation::Linear, {}, {}};
    Track cubic{0, AnimPath::Rotation, Interpolation::CubicSpline, {}, {}};
    for (int i = 0; i < 1309; ++i) {
      linear.times.push_back(i / 30.0f);
      cubic.times.push_back(i / 30.0f);
      linear.values.push_back(xyzw(raw));
      cubic.values.insert(cubic.values.end(), {glm::vec4(0.0f), xyzw(raw), glm::vec4(0.0f)});
    }
    clip.tracks = {linear, cubic};
    Clip built = Clip::build(clip, s).value();
    for (int i = 0; i < 1309 * 4; ++i) {
      double time = i / 120.0 + 1e-3;
      for (QuatInterpolation m : {QuatInterpolation::Slerp, QuatInterpolation::Nlerp})
        ASSERT_LE(maxDiff(sampleQuat(built.tracks()[0], time, m), raw), 1e-6f) << "linear, time " << time;
      ASSERT_LE(maxDiff(sampleQuat(built.tracks()[1], time), raw), 1e-6f) << "cubic, time " << time;
    }
  }
}

// Keys a few ulps around the issue's, renormalised or not, whose own float dot
// rounds to 1 - 2^-23 or 1 + 2^-23: the two values next to 1 that a threshold on
// the dot can get wrong.
TEST(QuatRegression, NeighboursWhoseOwnDotRoundsOffOneHoldTheKey) {
  std::mt19937_64 rng(1309);
  Track cubic = cubicTrack();
  int below = 0, above = 0;
  for (int i = 0; i < 60000; ++i) {
    glm::quat k = perturb(kIssueKeys[i & 1], rng, 6);
    if (rng() & 1) k = glm::normalize(k);
    float d = glm::dot(k, k);
    if (d != 1.0f - 0x1p-23f && d != 1.0f + 0x1p-23f) continue;
    (d < 1.0f ? below : above)++;
    expectHoldsKey(k, cubic);
    if (HasFatalFailure()) return;
  }
  std::printf("  %d keys with dot 1 - 2^-23, %d with 1 + 2^-23\n", below, above);
  EXPECT_GE(below, 2000);
  EXPECT_GE(above, 2000);
}

// q and -q are one rotation: a Hermite between them held still, where it used to
// pass through zero (identity at the midpoint) and through its own rounding noise.
TEST(QuatRegression, CubicSplineBetweenOppositeSignsHoldsTheRotation) {
  Track cubic = cubicTrack();
  glm::quat q = glm::angleAxis(1.1f, glm::normalize(glm::vec3(1, -2, 3)));
  setKeys(cubic, q, -q);
  for (int i = 0; i <= 64; ++i) {
    float t = i / 64.0f;
    EXPECT_LT(angleBetween(toDouble(sampleQuat(cubic, t)), toDouble(q)), 1e-6) << "t=" << t;
  }
}

// Tangents that carry the curve exactly through zero at the midpoint: the keys'
// nlerp stands in, not identity.
TEST(QuatRegression, CubicSplineThroughZeroFallsBackToTheKeys) {
  Track cubic = cubicTrack();
  glm::quat q = glm::angleAxis(0.8f, glm::normalize(glm::vec3(2, 1, -1)));
  setKeys(cubic, q, q);
  cubic.values[2] = xyzw(q) * -4.0f;  // out-tangent of key 0
  cubic.values[3] = xyzw(q) * 4.0f;   // in-tangent of key 1
  glm::quat r = sampleQuat(cubic, 0.5);
  EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
  EXPECT_LT(angleBetween(toDouble(r), toDouble(q)), 1e-6);
}

}  // namespace
}  // namespace engine
