#include "render/pass_timers.h"

#include <algorithm>

namespace engine {

void PassTimers::begin(const std::string& pass) {
  auto it = std::find_if(timers_.begin(), timers_.end(), [&](const Timer& t) { return t.pass == pass; });
  if (it == timers_.end()) it = timers_.insert(timers_.end(), Timer{pass, gl::Query::create(GL_TIME_ELAPSED)});
  active_ = it->pending ? -1 : int(it - timers_.begin());
  if (active_ >= 0) it->query.begin();
}

void PassTimers::end() {
  if (active_ < 0) return;
  timers_[size_t(active_)].query.end();
  timers_[size_t(active_)].pending = true;
  active_ = -1;
}

void PassTimers::collect() {
  for (Timer& t : timers_) {
    if (!t.pending || !t.query.available()) continue;
    t.ms = double(t.query.result()) * 1e-6;
    t.pending = false;
  }
}

std::vector<PassTime> PassTimers::times() const {
  std::vector<PassTime> out;
  for (const Timer& t : timers_) out.push_back({t.pass, t.ms});
  return out;
}

}  // namespace engine
