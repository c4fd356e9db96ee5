// Quaternion interpolation, Srt matrices and dual quaternions at their extremes.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/math.h"

namespace engine {
namespace {

// Rotation angle between two unit quaternions; atan2 keeps tiny angles exact
// where acos of a dot product near 1 does not.
float angleBetween(const glm::quat& a, glm::quat b) {
  if (glm::dot(a, b) < 0.0f) b = -b;
  return 4.0f * std::atan2(glm::length(a - b), glm::length(a + b));
}

TEST(Slerp, IdenticalQuaternionsGiveTheSameRotation) {
  glm::quat q = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3)));
  for (float t : {0.0f, 0.3f, 1.0f}) {
    glm::quat r = slerp(q, q, t);
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
    EXPECT_LT(angleBetween(r, q), 1e-3f);
    EXPECT_FALSE(std::isnan(r.w));
  }
}

TEST(Slerp, NearlyIdenticalStaysUnitAndContinuous) {
  glm::quat a = glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
  // 2e-4 rad of rotation apart, |a - b| = 1e-4: the nlerp fallback.
  glm::quat b = glm::angleAxis(0.5f + 2e-4f, glm::vec3(0, 1, 0));
  ASSERT_LT(glm::length(a - b), kSlerpNlerpBelow);
  glm::quat prev = a;
  for (int i = 0; i <= 100; ++i) {
    glm::quat r = slerp(a, b, i / 100.0f);
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
    EXPECT_LT(angleBetween(r, prev), 1e-4f);
    prev = r;
  }
  EXPECT_LT(angleBetween(prev, b), 1e-4f);
}

TEST(Slerp, JustOutsideTheFallbackMatchesTheAngle) {
  // |a - b| just above the threshold: the slerp branch with a tiny sin(theta).
  glm::quat a(1, 0, 0, 0);
  glm::quat b = glm::angleAxis(2.2e-3f, glm::vec3(1, 0, 0));
  ASSERT_GT(glm::length(a - b), kSlerpNlerpBelow);
  glm::quat r = slerp(a, b, 0.5f);
  EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::angle(r), 1.1e-3f, 2e-5f);
}

TEST(Slerp, OppositeQuaternionsTakeTheShortArc) {
  glm::quat a = glm::angleAxis(0.4f, glm::vec3(0, 0, 1));
  glm::quat b = -glm::angleAxis(0.6f, glm::vec3(0, 0, 1));  // same rotation as +, other sign
  glm::quat r = slerp(a, b, 0.5f);
  EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
  EXPECT_LT(angleBetween(r, glm::angleAxis(0.5f, glm::vec3(0, 0, 1))), 1e-5f);
  // q and -q: no motion at all, not a full turn.
  glm::quat c = slerp(a, -a, 0.5f);
  EXPECT_LT(angleBetween(c, a), 1e-3f);
  EXPECT_NEAR(glm::length(c), 1.0f, 1e-6f);
}

TEST(Slerp, MatchesConstantAngularSpeed) {
  glm::quat a(1, 0, 0, 0);
  glm::quat b = glm::angleAxis(2.0f, glm::vec3(0, 1, 0));
  for (float t : {0.1f, 0.25f, 0.5f, 0.9f})
    EXPECT_NEAR(glm::angle(slerp(a, b, t)), 2.0f * t, 1e-5f);
}

TEST(Nlerp, ShortArcAndUnitLength) {
  glm::quat a = glm::angleAxis(0.2f, glm::vec3(1, 0, 0));
  glm::quat r = nlerp(a, -a, 0.5f);
  EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
  EXPECT_LT(angleBetween(r, a), 1e-3f);
  EXPECT_EQ(safeNormalize(glm::quat(0, 0, 0, 0)), glm::quat(1, 0, 0, 0));
}

TEST(SrtMatrix, IsTranslationTimesRotationTimesScale) {
  Srt srt{glm::vec3(2, 3, 4), glm::angleAxis(0.9f, glm::normalize(glm::vec3(1, 1, 0))), glm::vec3(5, -6, 7)};
  glm::mat4 expected = glm::translate(glm::mat4(1), srt.translation) * glm::mat4_cast(srt.rotation) *
                       glm::scale(glm::mat4(1), srt.scale);
  glm::mat4 m = toMatrix(srt);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], 1e-5f);
}

TEST(SrtMatrix, DecomposeRoundTripsIncludingMirror) {
  Srt srt{glm::vec3(-2, 0.5f, 3), glm::angleAxis(1.3f, glm::normalize(glm::vec3(0, 1, 1))), glm::vec3(1, 2, 3)};
  Srt back = decompose(toMatrix(srt));
  glm::mat4 a = toMatrix(srt), b = toMatrix(back);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-5f);
  Srt zero = decompose(glm::mat4(0.0f));
  EXPECT_FALSE(std::isnan(zero.rotation.w));
}

TEST(DualQuat, RoundTripsRigidTransforms) {
  glm::quat r = glm::angleAxis(2.5f, glm::normalize(glm::vec3(1, -2, 0.5f)));
  glm::vec3 t(3, -1, 2);
  DualQuat dq = makeDualQuat(r, t);
  glm::mat4 expected = toMatrix(Srt{glm::vec3(1), r, t});
  glm::mat4 m = toMatrix(dq);
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(m[c][k], expected[c][k], 1e-5f);
  glm::vec3 p(0.3f, 2, -4);
  glm::vec3 q = transformPoint(dq, p);
  glm::vec3 e = glm::vec3(expected * glm::vec4(p, 1));
  EXPECT_NEAR(glm::distance(q, e), 0.0f, 1e-5f);
  DualQuat fromMatrix = makeDualQuat(expected);
  EXPECT_NEAR(glm::distance(transformPoint(fromMatrix, p), e), 0.0f, 1e-5f);
}

TEST(DualQuat, BlendOfOppositeSignsDoesNotCancel) {
  DualQuat a = makeDualQuat(glm::angleAxis(0.3f, glm::vec3(0, 1, 0)), glm::vec3(1, 0, 0));
  DualQuat b{-a.real, -a.dual};  // the same transform
  DualQuat sum{a.real * 0.5f, a.dual * 0.5f};
  accumulate(sum, b, 0.5f);
  glm::mat4 m = toMatrix(sum), e = toMatrix(a);
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(m[c][k], e[c][k], 1e-5f);
}

}  // namespace
}  // namespace engine
