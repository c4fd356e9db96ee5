// Clip building and sampling: at keys, between keys, outside the keys, single
// keys, zero-length clips and every interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "anim/clip.h"
#include "anim/jobs.h"

namespace engine {
namespace {

Skeleton makeSkeleton(int joints) {
  RawSkeleton raw;
  for (int i = 0; i < joints; ++i) {
    raw.parents.push_back(i - 1);
    raw.restPose.push_back(Srt{});
  }
  return Skeleton::build(raw).value();
}

Track vec3Track(Interpolation interpolation, std::vector<float> times, std::vector<glm::vec3> values) {
  Track t;
  t.joint = 0;
  t.path = AnimPath::Translation;
  t.interpolation = interpolation;
  t.times = std::move(times);
  for (const glm::vec3& v : values) t.values.emplace_back(v, 0.0f);
  return t;
}

Track quatTrack(std::vector<float> times, std::vector<glm::quat> values) {
  Track t;
  t.joint = 0;
  t.path = AnimPath::Rotation;
  t.times = std::move(times);
  for (const glm::quat& q : values) t.values.emplace_back(q.x, q.y, q.z, q.w);
  return t;
}

TEST(Sampling, ExactlyAtKeysGivesTheKeyValues) {
  Track t = vec3Track(Interpolation::Linear, {0.0f, 0.5f, 2.0f}, {{0, 0, 0}, {1, 2, 3}, {-1, 0, 5}});
  EXPECT_EQ(sampleVec3(t, 0.0), glm::vec3(0, 0, 0));
  EXPECT_EQ(sampleVec3(t, 0.5), glm::vec3(1, 2, 3));
  EXPECT_EQ(sampleVec3(t, 2.0), glm::vec3(-1, 0, 5));
  glm::vec3 mid = sampleVec3(t, 1.25);
  EXPECT_NEAR(mid.x, 0.0f, 1e-6f);
  EXPECT_NEAR(mid.z, 4.0f, 1e-6f);
}

TEST(Sampling, HoldsFirstAndLastValuesOutsideTheKeys) {
  Track t = vec3Track(Interpolation::Linear, {1.0f, 2.0f}, {{1, 1, 1}, {2, 2, 2}});
  EXPECT_EQ(sampleVec3(t, 0.0), glm::vec3(1));
  EXPECT_EQ(sampleVec3(t, -5.0), glm::vec3(1));
  EXPECT_EQ(sampleVec3(t, 2.5), glm::vec3(2));
  EXPECT_EQ(sampleVec3(t, 1e9), glm::vec3(2));
}

TEST(Sampling, SingleKeyIsConstant) {
  for (Interpolation i : {Interpolation::Step, Interpolation::Linear}) {
    Track t = vec3Track(i, {0.3f}, {{4, 5, 6}});
    for (double time : {-1.0, 0.0, 0.3, 0.31, 100.0}) EXPECT_EQ(sampleVec3(t, time), glm::vec3(4, 5, 6));
  }
  Track cubic = vec3Track(Interpolation::CubicSpline, {0.3f}, {{9, 9, 9}, {4, 5, 6}, {9, 9, 9}});
  EXPECT_EQ(sampleVec3(cubic, 10.0), glm::vec3(4, 5, 6));
}

TEST(Sampling, StepTakesTheLastKeyAtOrBefore) {
  Track t = vec3Track(Interpolation::Step, {0.0f, 1.0f, 2.0f}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});
  EXPECT_EQ(sampleVec3(t, 0.999), glm::vec3(0));
  EXPECT_EQ(sampleVec3(t, 1.0), glm::vec3(1));
  EXPECT_EQ(sampleVec3(t, 1.999), glm::vec3(1));
  EXPECT_EQ(sampleVec3(t, 2.0), glm::vec3(2));
}

TEST(Sampling, CubicSplineScalesTangentsByTheKeyInterval) {
  // Values 0 -> 1 over 2 s with out/in tangents of 1 unit/s: at the middle the
  // Hermite basis gives 0.5 + (0.125 - 0.125) * 2 = 0.5; at s = 0.25 it gives
  // h01 = 0.15625, h10 * dt * 1 = 0.140625 * 2, h11 * dt * 1 = -0.046875 * 2.
  Track t = vec3Track(Interpolation::CubicSpline, {0.0f, 2.0f},
                      {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}});
  EXPECT_NEAR(sampleVec3(t, 1.0).x, 0.5f, 1e-6f);
  EXPECT_NEAR(sampleVec3(t, 0.5).x, 0.15625f + 2 * 0.140625f - 2 * 0.046875f, 1e-6f);
  EXPECT_EQ(sampleVec3(t, 0.0).x, 0.0f);
  EXPECT_EQ(sampleVec3(t, 2.0).x, 1.0f);
}

TEST(Sampling, RotationIsUnitAndShortestArc) {
  glm::quat a = glm::angleAxis(0.1f, glm::vec3(0, 1, 0));
  glm::quat b = -glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
  Track t = quatTrack({0.0f, 1.0f}, {a, b});
  glm::quat r = sampleQuat(t, 0.5);
  EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
  EXPECT_NEAR(std::abs(glm::dot(r, glm::angleAxis(0.2f, glm::vec3(0, 1, 0)))), 1.0f, 1e-6f);
}

TEST(ClipBuild, DurationIsTheLargestLastKey) {
  Skeleton s = makeSkeleton(2);
  RawClip raw;
  raw.tracks.push_back(vec3Track(Interpolation::Linear, {0.0f, 1.5f}, {{0, 0, 0}, {1, 1, 1}}));
  Track second = vec3Track(Interpolation::Linear, {0.5f, 3.25f}, {{0, 0, 0}, {1, 1, 1}});
  second.joint = 1;
  raw.tracks.push_back(second);
  auto clip = Clip::build(raw, s);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_DOUBLE_EQ(clip->duration(), 3.25);
}

TEST(ClipBuild, ZeroLengthClipSamplesItsOnlyPose) {
  Skeleton s = makeSkeleton(1);
  RawClip raw;
  raw.tracks.push_back(vec3Track(Interpolation::Linear, {0.0f}, {{7, 8, 9}}));
  auto clip = Clip::build(raw, s).value();
  EXPECT_EQ(clip.duration(), 0.0);
  std::vector<Srt> out(1);
  SamplingJob job{&clip, 0.0, s.restPose(), out};
  ASSERT_TRUE(job.run());
  EXPECT_EQ(out[0].translation, glm::vec3(7, 8, 9));
  auto empty = Clip::build(RawClip{}, s);
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(empty->duration(), 0.0);
}

TEST(ClipBuild, RejectsBadTracks) {
  Skeleton s = makeSkeleton(1);
  auto fails = [&](Track t, const std::string& needle) {
    RawClip raw{"walk", {t}, {}};
    auto clip = Clip::build(raw, s);
    ASSERT_FALSE(clip.ok());
    EXPECT_NE(clip.error().message.find(needle), std::string::npos) << clip.error().message;
    EXPECT_NE(clip.error().message.find("walk"), std::string::npos);
  };
  float nan = std::numeric_limits<float>::quiet_NaN();
  Track good = vec3Track(Interpolation::Linear, {0.0f, 1.0f}, {{0, 0, 0}, {1, 1, 1}});
  Track t = good;
  t.joint = 5;
  fails(t, "joint 5");
  t = good;
  t.times = {1.0f, 0.5f};
  fails(t, "key 1");
  t = good;
  t.times = {-1.0f, 0.5f};
  fails(t, "key 0");
  t = good;
  t.times = {0.0f, nan};
  fails(t, "key 1");
  t = good;
  t.values[1].y = nan;
  fails(t, "value 1");
  t = good;
  t.values.pop_back();
  fails(t, "1 values for 2 keys");
  t = good;
  t.interpolation = Interpolation::CubicSpline;
  fails(t, "2 values for 2 keys");
  t = good;
  t.times.clear();
  t.values.clear();
  fails(t, "no keys");
}

TEST(SamplingJob, ValidateRejectsBadSpans) {
  Skeleton s = makeSkeleton(2);
  RawClip raw;
  Track t = vec3Track(Interpolation::Linear, {0.0f}, {{1, 1, 1}});
  t.joint = 1;
  raw.tracks.push_back(t);
  Clip clip = Clip::build(raw, s).value();
  std::vector<Srt> out(2), small(1);
  EXPECT_TRUE((SamplingJob{&clip, 0.0, s.restPose(), out}.validate()));
  EXPECT_FALSE((SamplingJob{nullptr, 0.0, s.restPose(), out}.validate()));
  EXPECT_FALSE((SamplingJob{&clip, 0.0, s.restPose(), small}.run()));
  EXPECT_FALSE((SamplingJob{&clip, std::nan(""), s.restPose(), out}.run()));
  Skeleton one = makeSkeleton(1);
  EXPECT_FALSE((SamplingJob{&clip, 0.0, one.restPose(), small}.validate()));  // track joint 1 past 1 joint
}

}  // namespace
}  // namespace engine
