#include <gtest/gtest.h>

#include <cmath>

#include "app/clock.h"
#include "app/frame_stats.h"
#include "app/runner.h"

using namespace engine;

TEST(FixedStepClock, StepsAreDueOnlyForWholeSteps) {
  FixedStepClock clock(0.25);
  EXPECT_EQ(clock.advance(0.2), 0);
  EXPECT_EQ(clock.advance(0.1), 1);
  EXPECT_NEAR(clock.alpha(), 0.05 / 0.25, 1e-12);
}

TEST(FixedStepClock, LongStallsAreCapped) {
  FixedStepClock clock(1.0 / 60.0);
  EXPECT_EQ(clock.advance(100.0, 8), 8);
  EXPECT_EQ(clock.advance(0.0), 0);  // the backlog was dropped
}

TEST(FixedStepClock, TimeDoesNotDriftAfterManySteps) {
  // 10 million steps at 1/60 s (46 hours): an accumulated float or double sum would
  // drift; time is computed from the step count.
  FixedStepClock clock(1.0 / 60.0, 0.0);
  for (int i = 0; i < 10'000'000; ++i) clock.step();
  EXPECT_EQ(clock.time(), 10'000'000.0 / 60.0);
}

TEST(HeadlessFrameTime, LastFrameIsExactlyTheRequestedTime) {
  RunOptions o;
  o.frames = 7;
  o.dt = 0.1;
  o.time = 1e6 + 0.3;
  EXPECT_EQ(headlessFrameTime(o, 6), 1e6 + 0.3);
  EXPECT_NEAR(headlessFrameTime(o, 0), 1e6 + 0.3 - 0.6, 1e-9);
}

TEST(HeadlessFrameTime, DefaultsToStepsFromZero) {
  RunOptions o;
  o.frames = 3;
  o.dt = 0.5;
  EXPECT_EQ(headlessFrameTime(o, 0), 0.0);
  EXPECT_EQ(headlessFrameTime(o, 2), 1.0);
}

TEST(FrameStats, MedianP95Max) {
  std::vector<double> ms;
  for (int i = 1; i <= 100; ++i) ms.push_back(double(101 - i));  // unsorted on purpose
  const FrameSummary s = summarize(ms);
  EXPECT_EQ(s.frames, 100);
  EXPECT_DOUBLE_EQ(s.medianMs, 50.5);
  EXPECT_DOUBLE_EQ(s.p95Ms, 95.0);
  EXPECT_DOUBLE_EQ(s.maxMs, 100.0);
  EXPECT_DOUBLE_EQ(s.minMs, 1.0);
}

TEST(FrameStats, EmptyAndSingle) {
  EXPECT_EQ(summarize({}).frames, 0);
  const FrameSummary one = summarize({4.0});
  EXPECT_EQ(one.medianMs, 4.0);
  EXPECT_EQ(one.p95Ms, 4.0);
}
