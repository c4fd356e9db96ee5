#include "app/clock.h"

namespace engine {

int FixedStepClock::advance(double elapsedSeconds, int maxSteps) {
  if (elapsedSeconds > 0.0) accumulator_ += elapsedSeconds;
  int due = 0;
  while (accumulator_ >= dt_ && due < maxSteps) {
    accumulator_ -= dt_;
    ++due;
  }
  if (due == maxSteps && accumulator_ >= dt_) accumulator_ = 0.0;  // drop the backlog
  return due;
}

}  // namespace engine
