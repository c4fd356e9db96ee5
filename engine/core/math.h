#pragma once
// Math on GLM shared by asset, anim and render: Srt transforms, quaternion
// interpolation and dual quaternions. Header-only so that engine_core's build
// needs no change; every function is small enough to inline.
//
// Matrices are column-major and act on column vectors (glTF/OpenGL order), so a
// local matrix is T * R * S. The course writes the same matrix in row-vector
// order as Scale * Rotation * Translation.
#include <cmath>
#include <limits>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace engine {

// Scale, rotation, translation: a node's local transform, kept apart so that
// animation can interpolate each part on its own.
struct Srt {
  glm::vec3 scale{1.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order: w, x, y, z
  glm::vec3 translation{0.0f};
};

inline glm::mat4 toMatrix(const Srt& srt) {
  glm::mat3 r = glm::mat3_cast(srt.rotation);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(r[0] * srt.scale.x, 0.0f);
  m[1] = glm::vec4(r[1] * srt.scale.y, 0.0f);
  m[2] = glm::vec4(r[2] * srt.scale.z, 0.0f);
  m[3] = glm::vec4(srt.translation, 1.0f);
  return m;
}

// parent * local where local's bottom row is (0, 0, 0, 1), as toMatrix makes it:
// each column sums only the terms local has, in a tree, ((p0 x + p1 y) + p2 z) and
// ((p0 tx + p1 ty) + (p2 tz + p3)), so that a chain of joints waits on two additions
// per joint, not three. LocalToModelJob computes exactly this, four lanes at a time.
inline glm::mat4 timesAffine(const glm::mat4& p, const glm::mat4& local) {
  glm::mat4 out;
  for (int c = 0; c < 3; ++c) out[c] = (p[0] * local[c].x + p[1] * local[c].y) + p[2] * local[c].z;
  out[3] = (p[0] * local[3].x + p[1] * local[3].y) + (p[2] * local[3].z + p[3]);
  return out;
}

// Splits an affine matrix into Srt the way three.js does: scale = column lengths,
// a negative determinant flips the x scale, rotation from the unscaled columns.
// Shear cannot be represented and is lost (glTF forbids it on animated nodes).
inline Srt decompose(const glm::mat4& m) {
  Srt srt;
  srt.translation = glm::vec3(m[3]);
  glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  srt.scale = {glm::length(c0), glm::length(c1), glm::length(c2)};
  if (glm::determinant(glm::mat3(m)) < 0.0f) srt.scale.x = -srt.scale.x;
  // A zero scale leaves no rotation to recover; identity is as good as any.
  if (srt.scale.x == 0.0f || srt.scale.y == 0.0f || srt.scale.z == 0.0f) return srt;
  glm::mat3 r(c0 / srt.scale.x, c1 / srt.scale.y, c2 / srt.scale.z);
  srt.rotation = glm::normalize(glm::quat_cast(r));
  return srt;
}

// Whether q has a direction to normalise to. Below FLT_MIN the squared length is
// subnormal and has lost the bits that would make q / |q| unit length.
inline bool hasDirection(const glm::quat& q) {
  float len2 = glm::dot(q, q);
  return len2 >= std::numeric_limits<float>::min() && std::isfinite(len2);
}

// Normalises, falling back to identity for a zero (or NaN) quaternion so that bad
// data yields a valid rotation instead of NaNs.
inline glm::quat safeNormalize(const glm::quat& q) {
  if (!hasDirection(q)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return q * (1.0f / std::sqrt(glm::dot(q, q)));
}

// Normalised lerp along the shortest arc: cheap, and the right tool for blending
// several poses, where the exact angular speed does not matter. After the flip the
// dot is >= 0, so for unit keys |(1-t)a + tb|^2 >= 1/2 on [0, 1]: never zero.
inline glm::quat nlerp(const glm::quat& a, glm::quat b, float t) {
  if (glm::dot(a, b) < 0.0f) b = -b;
  return safeNormalize(a * (1.0f - t) + b * t);
}

// Below this |a - b| (about the 4D angle theta between unit a and b, as |a - b| =
// 2 sin(theta/2)) slerp hands over to nlerp. nlerp strays from slerp by
// t(1-t)|1-2t| theta^3 / 6 <= theta^3 / (36 sqrt 3) in the 4D angle, twice that in
// rotation angle: under 4e-11 rad here, far below the 6e-8 spacing of floats near
// 1, so the two agree to float precision. Above it sin(theta) >= 1e-3 and the
// weights' division is well conditioned. The test is on |a - b|, computed from the
// differences, and not on the dot: 1 - 1e-7f rounds to 1 - 2^-23, which is also
// what a unit key's dot with itself can round to, and such identical keys once
// skipped the nlerp branch for sin(0) / sin(0), a NaN that became identity.
inline constexpr float kSlerpNlerpBelow = 1e-3f;

// Spherical lerp along the shortest arc (b is negated when the dot is negative, as
// q and -q are the same rotation). theta = 2 atan2(|a-b|, |a+b|) is accurate on all
// of 0..pi/2, the flip's range, where acos(dot) loses half the digits near 1.
// sin(theta) comes from the same two lengths, 2|a-b||a+b| / (|a-b|^2 + |a+b|^2),
// which saves a sin. The result is renormalised so that keys a little off unit
// length still give a rotation; a NaN key fails the threshold test and becomes
// identity through nlerp's safeNormalize.
// slerp is split in two so that a caller interpolating many times between the same
// two keys (animation playback) computes the arc, with its atan2, once per key pair:
// slerpArc(a, b) depends on the keys only, slerpAt on the arc and t. slerp is the
// two in a row, so the three give bit-identical results.
struct SlerpArc {
  glm::quat b{1.0f, 0.0f, 0.0f, 0.0f};  // the second key, in the first's hemisphere
  float theta = 0.0f, invSin = 0.0f;
  bool nlerp = true;  // below kSlerpNlerpBelow
};

inline SlerpArc slerpArc(const glm::quat& a, glm::quat b) {
  if (glm::dot(a, b) < 0.0f) b = -b;
  float minus2 = glm::dot(a - b, a - b), plus2 = glm::dot(a + b, a + b);
  if (!(minus2 >= kSlerpNlerpBelow * kSlerpNlerpBelow)) return {b, 0.0f, 0.0f, true};
  float minus = std::sqrt(minus2), plus = std::sqrt(plus2);
  float theta = 2.0f * std::atan2(minus, plus);
  float invSin = (minus2 + plus2) / (2.0f * minus * plus);
  return {b, theta, invSin, false};
}

// sin x on slerp's angles, 0..pi/2 (a little past it is as good): an odd polynomial
// of degree 11 in Horner form, within 2 ulp of std::sin and 1.3e-7 relative of the
// true sine there (every float of the range checked). Not std::sin, so that the SoA
// sampling (anim/key_blocks.cpp) evaluates it four lanes at a time with these
// coefficients in this order and gets the bits of slerpAt.
inline constexpr float kSinPolynomial[5] = {-2.3889859e-08f, 2.7525562e-06f, -1.9840874e-04f, 8.3333293e-03f,
                                            -1.6666666e-01f};
inline float slerpSin(float x) {
  const float x2 = x * x;
  float p = kSinPolynomial[0];
  for (int i = 1; i < 5; ++i) p = p * x2 + kSinPolynomial[i];
  return x + x * x2 * p;
}

inline glm::quat slerpAt(const glm::quat& a, const SlerpArc& arc, float t) {
  if (arc.nlerp) return safeNormalize(a * (1.0f - t) + arc.b * t);
  return safeNormalize(a * (slerpSin((1.0f - t) * arc.theta) * arc.invSin) +
                       arc.b * (slerpSin(t * arc.theta) * arc.invSin));
}

inline glm::quat slerp(const glm::quat& a, const glm::quat& b, float t) { return slerpAt(a, slerpArc(a, b), t); }

// Dual quaternion: real part = rotation, dual part = 0.5 * translation * rotation.
// Blending these instead of matrices (DQS) keeps the skin's volume at twisted
// joints; it represents rotation and translation only, no scale.
struct DualQuat {
  glm::quat real{1.0f, 0.0f, 0.0f, 0.0f};
  glm::quat dual{0.0f, 0.0f, 0.0f, 0.0f};
};

inline DualQuat makeDualQuat(const glm::quat& rotation, const glm::vec3& translation) {
  glm::quat t(0.0f, translation.x, translation.y, translation.z);
  return {rotation, (t * rotation) * 0.5f};
}

// Builds from a rigid matrix; any scale in the columns is divided out first.
inline DualQuat makeDualQuat(const glm::mat4& m) {
  glm::mat3 r(glm::normalize(glm::vec3(m[0])), glm::normalize(glm::vec3(m[1])),
              glm::normalize(glm::vec3(m[2])));
  return makeDualQuat(glm::normalize(glm::quat_cast(r)), glm::vec3(m[3]));
}

// Adds w * dq to acc, flipping dq into acc's hemisphere so that the sum does not
// cancel (q and -q are the same rotation). Start acc at zero and the first add
// sets the hemisphere.
inline void accumulate(DualQuat& acc, const DualQuat& dq, float w) {
  if (glm::dot(acc.real, dq.real) < 0.0f) w = -w;
  acc.real += dq.real * w;
  acc.dual += dq.dual * w;
}

inline DualQuat normalize(const DualQuat& dq) {
  float len = glm::length(dq.real);
  if (!(len > 0.0f)) return DualQuat{};
  return {dq.real * (1.0f / len), dq.dual * (1.0f / len)};
}

// Expects a normalised dual quaternion.
inline glm::vec3 translationOf(const DualQuat& dq) {
  glm::quat t = (dq.dual * 2.0f) * glm::conjugate(dq.real);
  return {t.x, t.y, t.z};
}

inline glm::mat4 toMatrix(const DualQuat& dq) {
  DualQuat n = normalize(dq);
  glm::mat4 m = glm::mat4_cast(n.real);
  m[3] = glm::vec4(translationOf(n), 1.0f);
  return m;
}

// Applies a normalised dual quaternion to a point without building a matrix.
inline glm::vec3 transformPoint(const DualQuat& dq, const glm::vec3& p) {
  return dq.real * p + translationOf(dq);
}

}  // namespace engine
