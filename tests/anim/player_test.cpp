// Loop modes, long play times, speed, seeking and cross-fades.
#include <gtest/gtest.h>

#include <cmath>

#include "anim/player.h"

namespace engine {
namespace {

TEST(WrapTime, RepeatFollowsTheThreeJsRule) {
  const double d = 1.7083333730697632;
  EXPECT_DOUBLE_EQ(wrapTime(0.0, d, LoopMode::Repeat), 0.0);
  EXPECT_DOUBLE_EQ(wrapTime(d, d, LoopMode::Repeat), 0.0);  // t = D samples 0
  EXPECT_NEAR(wrapTime(1.5 * d, d, LoopMode::Repeat), 0.5 * d, 1e-12);
  EXPECT_NEAR(wrapTime(-0.3, d, LoopMode::Repeat), d - 0.3, 1e-12);
}

TEST(WrapTime, MillionSecondsMatchesFmodTo1ns) {
  const double d = 1.6666666269302368;
  for (double t : {1e6, 1e6 + 0.123, 3.7e6}) {
    double expected = std::fmod(t, d);
    EXPECT_NEAR(wrapTime(t, d, LoopMode::Repeat), expected, 1e-9) << t;
  }
}

TEST(WrapTime, ClampAndPingPong) {
  EXPECT_DOUBLE_EQ(wrapTime(5.0, 2.0, LoopMode::Clamp), 2.0);
  EXPECT_DOUBLE_EQ(wrapTime(-1.0, 2.0, LoopMode::Clamp), 0.0);
  EXPECT_DOUBLE_EQ(wrapTime(2.5, 2.0, LoopMode::PingPong), 1.5);
  EXPECT_DOUBLE_EQ(wrapTime(4.5, 2.0, LoopMode::PingPong), 0.5);
  EXPECT_DOUBLE_EQ(wrapTime(-0.5, 2.0, LoopMode::PingPong), 0.5);
}

TEST(LoopModeText, ParsesTheThreeNames) {
  EXPECT_EQ(parseLoopMode("repeat"), LoopMode::Repeat);
  EXPECT_EQ(parseLoopMode("clamp"), LoopMode::Clamp);
  EXPECT_EQ(parseLoopMode("pingpong"), LoopMode::PingPong);
  EXPECT_FALSE(parseLoopMode("once").has_value());
}

TEST(WrapTime, ZeroDurationAndBadTimesGiveZero) {
  EXPECT_EQ(wrapTime(3.0, 0.0, LoopMode::Repeat), 0.0);
  EXPECT_EQ(wrapTime(3.0, 0.0, LoopMode::PingPong), 0.0);
  EXPECT_EQ(wrapTime(NAN, 1.0, LoopMode::Repeat), 0.0);
  EXPECT_EQ(wrapTime(INFINITY, 1.0, LoopMode::Clamp), 0.0);
}

class PlayerTest : public ::testing::Test {
 protected:
  PlayerTest() {
    RawSkeleton raw{{-1}, {Srt{}}, {}};
    skeleton_ = Skeleton::build(raw).value();
    walk_ = makeClip(glm::vec3(0), glm::vec3(2, 0, 0));
    run_ = makeClip(glm::vec3(0, 10, 0), glm::vec3(0, 10, 0));
  }
  Clip makeClip(glm::vec3 a, glm::vec3 b) {
    Track t{0, AnimPath::Translation, Interpolation::Linear, {0.0f, 2.0f}, {glm::vec4(a, 0), glm::vec4(b, 0)}};
    return Clip::build(RawClip{"", {t}, {}}, skeleton_).value();
  }
  Skeleton skeleton_;
  Clip walk_, run_;
};

TEST_F(PlayerTest, SpeedAndNegativeSpeed) {
  Player player(skeleton_);
  player.play(walk_);
  player.setSpeed(2.0);
  player.update(0.25);
  EXPECT_DOUBLE_EQ(player.localTime(), 0.5);
  player.setSpeed(-1.0);
  player.update(1.0);  // back past 0: wraps to the end
  EXPECT_DOUBLE_EQ(player.localTime(), 1.5);
  std::vector<Srt> pose(1);
  ASSERT_TRUE(player.evaluate(pose));
  EXPECT_NEAR(pose[0].translation.x, 1.5f, 1e-6f);
}

TEST_F(PlayerTest, SeekAndClamp) {
  Player player(skeleton_);
  player.play(walk_, LoopMode::Clamp);
  player.seek(10.0);
  EXPECT_DOUBLE_EQ(player.localTime(), 2.0);
  std::vector<Srt> pose(1);
  ASSERT_TRUE(player.evaluate(pose));
  EXPECT_EQ(pose[0].translation, glm::vec3(2, 0, 0));
}

TEST_F(PlayerTest, CrossFadeBlendsByWeight) {
  Player player(skeleton_);
  player.play(walk_);
  player.update(1.0);  // walk at x = 1
  player.crossFade(run_, 1.0);
  player.update(0.25);  // walk at x = 1.25, fade 25%
  EXPECT_FLOAT_EQ(player.fadeWeight(), 0.25f);
  std::vector<Srt> pose(1);
  ASSERT_TRUE(player.evaluate(pose));
  EXPECT_NEAR(pose[0].translation.x, 0.75f * 1.25f, 1e-5f);
  EXPECT_NEAR(pose[0].translation.y, 0.25f * 10.0f, 1e-5f);
  player.update(1.0);  // fade over
  EXPECT_FLOAT_EQ(player.fadeWeight(), 1.0f);
  ASSERT_TRUE(player.evaluate(pose));
  EXPECT_EQ(pose[0].translation, glm::vec3(0, 10, 0));
}

TEST_F(PlayerTest, EvaluateWithoutClipOrWithWrongSpanFails) {
  Player player(skeleton_);
  std::vector<Srt> pose(1), wrong(3);
  EXPECT_FALSE(player.evaluate(pose));
  player.play(walk_);
  EXPECT_FALSE(player.evaluate(wrong));
}

}  // namespace
}  // namespace engine
