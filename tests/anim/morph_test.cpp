// Morph target weights at their extremes: sampling STEP, LINEAR and CUBICSPLINE
// tracks before, on, between and after keys, far from zero and with many targets;
// building clips against a MorphLayout; the sampling, blending and morphing jobs;
// and the player's cross-fade of weights.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "anim/clip.h"
#include "anim/jobs.h"
#include "anim/player.h"

namespace engine {
namespace {

Skeleton oneJoint() {
  RawSkeleton raw;
  raw.parents = {-1};
  raw.restPose = {Srt{}};
  return Skeleton::build(raw).value();
}

// Node 0 with `targets` targets and the given rest weights.
MorphLayout layoutOf(std::vector<float> rest) {
  MorphLayout layout;
  layout.first = {0};
  layout.targets = {static_cast<int>(rest.size())};
  layout.restWeights = std::move(rest);
  return layout;
}

MorphTrack track(Interpolation interpolation, int targets, std::vector<float> times, std::vector<float> values) {
  return MorphTrack{0, 0, targets, interpolation, std::move(times), std::move(values)};
}

std::vector<float> sampled(const MorphTrack& t, double time) {
  std::vector<float> out(static_cast<std::size_t>(t.targets), -99.0f);
  sampleWeights(t, time, out);
  return out;
}

using Weights = std::vector<float>;

TEST(MorphSampling, StepHoldsEachKeyUntilTheNext) {
  const MorphTrack t = track(Interpolation::Step, 2, {0.5f, 1.0f, 2.0f}, {0, 1, 0.25f, -0.5f, 1.5f, 2});
  EXPECT_EQ(sampled(t, -1e9), (Weights{0, 1}));  // before the first key: the first
  EXPECT_EQ(sampled(t, 0.0), (Weights{0, 1}));
  EXPECT_EQ(sampled(t, 0.5), (Weights{0, 1}));  // exactly on keys
  EXPECT_EQ(sampled(t, 1.0), (Weights{0.25f, -0.5f}));
  EXPECT_EQ(sampled(t, 1.999999), (Weights{0.25f, -0.5f}));
  EXPECT_EQ(sampled(t, 2.0), (Weights{1.5f, 2}));
  EXPECT_EQ(sampled(t, 1e9), (Weights{1.5f, 2}));  // after the last: the last
}

TEST(MorphSampling, LinearIsExactOnKeysAndLerpsBetween) {
  const MorphTrack t = track(Interpolation::Linear, 3, {0.0f, 2.0f}, {0, 1, -1, 1, 0, 3});
  EXPECT_EQ(sampled(t, 0.0), (Weights{0, 1, -1}));
  EXPECT_EQ(sampled(t, 2.0), (Weights{1, 0, 3}));
  EXPECT_EQ(sampled(t, 0.5), (Weights{0.25f, 0.75f, 0}));
  EXPECT_EQ(sampled(t, 1.5), (Weights{0.75f, 0.25f, 2}));
  EXPECT_EQ(sampled(t, -3.0), (Weights{0, 1, -1}));
  EXPECT_EQ(sampled(t, 7.0), (Weights{1, 0, 3}));
}

// glTF CUBICSPLINE with n targets: per key n in-tangents, n values, n
// out-tangents. At s = 1/2 the Hermite basis is (1/2, dt/8, 1/2, -dt/8).
TEST(MorphSampling, CubicSplineReadsTheThreeBlocksPerKey) {
  const float dt = 2.0f;
  // key 0: in (9, 9), value (0, 1), out (1, -2); key 1: in (4, 0), value (2, 3), out (9, 9)
  const MorphTrack t = track(Interpolation::CubicSpline, 2, {1.0f, 1.0f + dt},
                             {9, 9, 0, 1, 1, -2, /**/ 4, 0, 2, 3, 9, 9});
  EXPECT_EQ(sampled(t, 1.0), (Weights{0, 1}));  // on the keys: the values, not the tangents
  EXPECT_EQ(sampled(t, 3.0), (Weights{2, 3}));
  EXPECT_EQ(sampled(t, 0.0), (Weights{0, 1}));
  EXPECT_EQ(sampled(t, 50.0), (Weights{2, 3}));
  const auto mid = sampled(t, 2.0);
  EXPECT_NEAR(mid[0], 0.5f * 0 + dt / 8 * 1 + 0.5f * 2 - dt / 8 * 4, 1e-6f);
  EXPECT_NEAR(mid[1], 0.5f * 1 + dt / 8 * -2 + 0.5f * 3 - dt / 8 * 0, 1e-6f);
  // The curve leaves key 0 with its out-tangent: slope (1, -2) per second.
  const double h = 1e-3;
  const auto near0 = sampled(t, 1.0 + h);
  EXPECT_NEAR((near0[0] - 0.0f) / h, 1.0, 2e-2);
  EXPECT_NEAR((near0[1] - 1.0f) / h, -2.0, 2e-2);
}

// Keys a day into a clip: float key times are exact there, the double playhead
// resolves a quarter of the interval.
TEST(MorphSampling, FarFromZero) {
  const MorphTrack t = track(Interpolation::Linear, 1, {86400.0f, 86401.0f}, {0, 1});
  EXPECT_EQ(sampled(t, 86400.25)[0], 0.25f);
  EXPECT_EQ(sampled(t, 86400.0)[0], 0.0f);
  EXPECT_EQ(sampled(t, 86401.0)[0], 1.0f);
  EXPECT_EQ(sampled(t, 1e12)[0], 1.0f);
}

TEST(MorphSampling, ManyTargetsEachFollowTheirOwnColumn) {
  const int targets = 300;
  std::vector<float> values;
  for (int key = 0; key < 3; ++key)
    for (int i = 0; i < targets; ++i) values.push_back(float(i) * 0.01f + float(key));
  const MorphTrack t = track(Interpolation::Linear, targets, {0.0f, 1.0f, 2.0f}, values);
  const auto w = sampled(t, 1.5);
  for (int i = 0; i < targets; ++i) EXPECT_NEAR(w[size_t(i)], float(i) * 0.01f + 1.5f, 1e-5f) << i;
}

TEST(MorphClip, BuildPlacesTracksAndExtendsTheDuration) {
  const Skeleton s = oneJoint();
  RawClip raw{"smile", {}, {track(Interpolation::Linear, 2, {0.0f, 3.5f}, {0, 0, 1, 1})}};
  raw.morphTracks[0].first = -7;  // set by build, whatever the raw track says
  MorphLayout layout;
  layout.first = {4};
  layout.targets = {2};
  layout.restWeights = {9, 9, 9, 9, 0.5f, 0.5f};
  auto clip = Clip::build(raw, s, layout);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->morphTracks()[0].first, 4);
  EXPECT_DOUBLE_EQ(clip->duration(), 3.5);
  std::vector<float> out(6);
  ASSERT_TRUE((MorphSamplingJob{&*clip, 1.75, layout.restWeights, out}.run()));
  EXPECT_EQ(out, (Weights{9, 9, 9, 9, 0.5f, 0.5f}));
}

TEST(MorphClip, BuildRejectsBadTracks) {
  const Skeleton s = oneJoint();
  const MorphLayout layout = layoutOf({0, 0});
  auto fails = [&](MorphTrack t, const MorphLayout& l, const std::string& needle) {
    auto clip = Clip::build(RawClip{"smile", {}, {t}}, s, l);
    ASSERT_FALSE(clip.ok()) << needle;
    EXPECT_NE(clip.error().message.find(needle), std::string::npos) << clip.error().message;
    EXPECT_NE(clip.error().message.find("smile"), std::string::npos) << clip.error().message;
  };
  const MorphTrack good = track(Interpolation::Linear, 2, {0.0f, 1.0f}, {0, 0, 1, 1});
  ASSERT_TRUE(Clip::build(RawClip{"smile", {}, {good}}, s, layout).ok());
  fails(good, MorphLayout{}, "node 0 has no morph targets");
  MorphTrack t = good;
  t.node = 3;
  fails(t, layout, "node 3 has no morph targets");
  fails(good, layoutOf({0, 0, 0}), "2 weights per key, node 0 has 3 morph targets");
  t = good;
  t.values.pop_back();
  fails(t, layout, "3 weights for 2 keys of 2 targets");
  t = good;
  t.interpolation = Interpolation::CubicSpline;
  fails(t, layout, "4 weights for 2 keys of 2 targets");
  t = good;
  t.values[2] = std::numeric_limits<float>::infinity();
  fails(t, layout, "weight 2 is NaN or infinite");
  t = good;
  t.times = {1.0f, 0.5f};
  fails(t, layout, "key 1");
  t = good;
  t.times.clear();
  fails(t, layout, "no keys");
}

TEST(MorphSamplingJob, ValidateRejectsBadSpans) {
  const Skeleton s = oneJoint();
  const MorphLayout layout = layoutOf({0.5f, 0.5f});
  const Clip clip =
      Clip::build(RawClip{"", {}, {track(Interpolation::Linear, 2, {0.0f}, {1, 1})}}, s, layout).value();
  std::vector<float> out(2), small(1);
  EXPECT_TRUE((MorphSamplingJob{&clip, 0.0, layout.restWeights, out}.validate()));
  EXPECT_FALSE((MorphSamplingJob{nullptr, 0.0, layout.restWeights, out}.validate()));
  EXPECT_FALSE((MorphSamplingJob{&clip, std::nan(""), layout.restWeights, out}.run()));
  EXPECT_FALSE((MorphSamplingJob{&clip, 0.0, layout.restWeights, small}.run()));
  const std::vector<float> rest1{0.0f};
  EXPECT_FALSE((MorphSamplingJob{&clip, 0.0, rest1, small}.run()));  // the track runs past the array
  // A clip without morph tracks fits any array, an empty one too.
  const Clip bones = Clip::build(RawClip{}, s).value();
  EXPECT_TRUE((MorphSamplingJob{&bones, 0.0, {}, {}}.run()));
}

TEST(MorphBlendingJob, NormalisesLayersAndFallsBackToRest) {
  const std::vector<float> rest{0.1f, 0.2f}, a{1, 0}, b{0, 1};
  std::vector<float> out(2);
  std::vector<MorphBlendingJob::Layer> layers{{a, 1.0f}, {b, 3.0f}};
  ASSERT_TRUE((MorphBlendingJob{layers, rest, out}.run()));
  EXPECT_FLOAT_EQ(out[0], 0.25f);
  EXPECT_FLOAT_EQ(out[1], 0.75f);
  layers = {{a, 0.0f}, {b, 0.0f}};
  ASSERT_TRUE((MorphBlendingJob{layers, rest, out}.run()));
  EXPECT_EQ(out, rest);
  layers = {{a, -1.0f}};
  EXPECT_FALSE((MorphBlendingJob{layers, rest, out}.run()));
  const std::vector<float> shortLayer{1};
  layers = {{shortLayer, 1.0f}};
  EXPECT_FALSE((MorphBlendingJob{layers, rest, out}.run()));
}

// Two vertices, two targets (target-major deltas), every attribute.
struct MorphFixture {
  std::vector<glm::vec3> positions{{0, 0, 0}, {1, 0, 0}};
  std::vector<glm::vec3> normals{{0, 0, 1}, {0, 0, 1}};
  std::vector<glm::vec4> tangents{{1, 0, 0, -1}, {1, 0, 0, 1}};
  std::vector<glm::vec3> positionDeltas{{0, 1, 0}, {0, 2, 0}, /* target 1 */ {1, 0, 0}, {0, 0, 4}};
  std::vector<glm::vec3> normalDeltas{{1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  std::vector<glm::vec3> tangentDeltas{{0, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  std::vector<float> weights{0.5f, 2.0f};
  std::vector<glm::vec3> outPositions = std::vector<glm::vec3>(2), outNormals = std::vector<glm::vec3>(2);
  std::vector<glm::vec4> outTangents = std::vector<glm::vec4>(2);

  MorphJob job() {
    return MorphJob{weights, positions, positionDeltas, outPositions, normals, normalDeltas,
                    outNormals, tangents, tangentDeltas, outTangents};
  }
};

TEST(MorphJob, AddsWeightedDeltasToEveryAttribute) {
  MorphFixture f;
  ASSERT_TRUE(f.job().run());
  EXPECT_EQ(f.outPositions[0], glm::vec3(2, 0.5f, 0));
  EXPECT_EQ(f.outPositions[1], glm::vec3(1, 1, 8));
  EXPECT_EQ(f.outNormals[0], glm::vec3(0.5f, 2, 1));  // not renormalised
  EXPECT_EQ(f.outNormals[1], glm::vec3(0, 0, 1));
  EXPECT_EQ(f.outTangents[0], glm::vec4(1, 0.5f, 0, -1));  // w, the handedness, is kept
  EXPECT_EQ(f.outTangents[1], glm::vec4(1, 0, 2, 1));
}

TEST(MorphJob, ZeroWeightsAndMissingDeltasLeaveTheBase) {
  MorphFixture f;
  f.weights = {0.0f, 0.0f};
  f.normalDeltas.clear();  // no target moves the normals
  ASSERT_TRUE(f.job().run());
  EXPECT_EQ(f.outPositions, f.positions);
  EXPECT_EQ(f.outNormals, f.normals);
  // Zero weights are skipped, so even a NaN delta cannot leak in.
  f.positionDeltas[0].x = std::numeric_limits<float>::quiet_NaN();
  ASSERT_TRUE(f.job().run());
  EXPECT_EQ(f.outPositions, f.positions);
}

TEST(MorphJob, InPlaceEqualsSeparateOutputs) {
  MorphFixture f;
  ASSERT_TRUE(f.job().run());
  MorphFixture g;
  MorphJob inPlace = g.job();
  inPlace.outPositions = g.positions;
  inPlace.outNormals = g.normals;
  inPlace.outTangents = g.tangents;
  ASSERT_TRUE(inPlace.run());
  EXPECT_EQ(g.positions, f.outPositions);
  EXPECT_EQ(g.normals, f.outNormals);
  EXPECT_EQ(g.tangents, f.outTangents);
}

TEST(MorphJob, ValidateRejectsSpansThatDoNotFit) {
  {
    MorphFixture f;
    f.weights.push_back(1.0f);  // three weights, deltas for two targets
    EXPECT_FALSE(f.job().validate());
  }
  {
    MorphFixture f;
    f.outPositions.pop_back();
    EXPECT_FALSE(f.job().validate());
  }
  {
    MorphFixture f;
    f.normalDeltas.pop_back();
    EXPECT_FALSE(f.job().run());
  }
  {
    MorphFixture f;
    f.outTangents.clear();
    EXPECT_FALSE(f.job().validate());
  }
  {
    MorphFixture f;
    MorphJob job = f.job();
    job.normals = {};  // optional attributes may be left out
    job.tangents = {};
    EXPECT_TRUE(job.validate());
  }
}

TEST(MorphPlayer, CrossFadeBlendsTheWeights) {
  const Skeleton s = oneJoint();
  const MorphLayout layout = layoutOf({0.0f, 0.0f});
  const Clip open = Clip::build(RawClip{"open", {}, {track(Interpolation::Step, 2, {0.0f}, {1, 0})}}, s, layout).value();
  const Clip shut = Clip::build(RawClip{"shut", {}, {track(Interpolation::Step, 2, {0.0f}, {0, 1})}}, s, layout).value();
  Player player(s, layout.restWeights);
  std::vector<Srt> locals(1);
  std::vector<float> weights(2);
  player.play(open);
  ASSERT_TRUE(player.evaluate(locals, weights));
  EXPECT_EQ(weights, (Weights{1, 0}));
  player.crossFade(shut, 1.0);
  player.update(0.25);
  ASSERT_TRUE(player.evaluate(locals, weights));
  EXPECT_FLOAT_EQ(weights[0], 0.75f);
  EXPECT_FLOAT_EQ(weights[1], 0.25f);
  player.update(1.0);
  ASSERT_TRUE(player.evaluate(locals, weights));
  EXPECT_EQ(weights, (Weights{0, 1}));
  std::vector<float> wrongSize(3);
  EXPECT_FALSE(player.evaluate(locals, wrongSize));
  EXPECT_TRUE(player.evaluate(locals));  // the weights are optional
}

}  // namespace
}  // namespace engine
