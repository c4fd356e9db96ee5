#pragma once
// GPU time per pass (a GL_TIME_ELAPSED query each), as SceneRenderer::passTimes
// reports it: a pass's query is begun only once its last result is read, so
// reading never waits and a figure may be a frame or two old. Not part of the
// engine's interface.
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/resources.h"
#include "render/scene_stats.h"

namespace engine {

class PassTimers {
 public:
  // One pass at a time, named as --describe names it.
  void begin(const std::string& pass);
  void end();
  // `run` timed as `pass`.
  template <typename Run>
  Status time(const std::string& pass, Run run) {
    begin(pass);
    const Status status = run();
    end();
    return status;
  }
  // Takes the results the GL has.
  void collect();
  // Every pass's latest, in the order the frame first drew them.
  std::vector<PassTime> times() const;

 private:
  struct Timer {
    std::string pass;
    gl::Query query;
    bool pending = false;
    double ms = 0.0;
  };
  std::vector<Timer> timers_;
  int active_ = -1;
};

}  // namespace engine
