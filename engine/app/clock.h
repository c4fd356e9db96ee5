#pragma once
// Fixed-step simulation time, kept in double: at 60 Hz a float clock loses
// millisecond precision after a few hours, a double keeps it for millennia.
#include <cstdint>

namespace engine {

class FixedStepClock {
 public:
  explicit FixedStepClock(double dt, double start = 0.0) : dt_(dt), start_(start) {}

  // Adds real elapsed seconds; returns how many fixed steps are now due. Long
  // stalls are capped so a paused debugger does not trigger thousands of steps.
  int advance(double elapsedSeconds, int maxSteps = 8);
  // Time after the last step, computed from the step count, so it does not drift
  // by accumulated rounding.
  double time() const { return start_ + double(steps_) * dt_; }
  // Fraction of a step between the last step and now (for interpolation).
  double alpha() const { return accumulator_ / dt_; }
  void step() { ++steps_; }
  double dt() const { return dt_; }
  std::int64_t steps() const { return steps_; }

 private:
  double dt_;
  double start_;
  double accumulator_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace engine
