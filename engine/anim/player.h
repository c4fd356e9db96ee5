#pragma once
// Plays clips on a skeleton: keeps the playhead in double (a character left
// running for days still samples the right frame), loops, changes speed (negative
// plays backwards), seeks, and cross-fades from one clip to the next.
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "anim/clip.h"
#include "anim/skeleton.h"

namespace engine {

enum class LoopMode {
  Repeat,    // t - D * floor(t / D): t = D samples 0, negative times wrap too
  Clamp,     // clamp(t, 0, D): holds the last pose after the end
  PingPong,  // forwards, then backwards, period 2D
};

// "repeat", "clamp" or "pingpong" (command lines, scene files); nullopt otherwise.
std::optional<LoopMode> parseLoopMode(std::string_view text);

// Clip-local time for playhead `time` on a clip of `duration` seconds. A clip of
// zero duration always samples 0.
double wrapTime(double time, double duration, LoopMode mode);

class Player {
 public:
  // Allocates the scratch poses (and morph weights, laid out like
  // `restMorphWeights`) once; evaluate() never allocates (play and crossFade size
  // the clip's sampling context).
  explicit Player(const Skeleton& skeleton, std::span<const float> restMorphWeights = {});

  // Starts `clip` at time 0 at once, cancelling any fade.
  void play(const Clip& clip, LoopMode mode = LoopMode::Repeat);
  // Starts `clip` at 0 and blends to it over `seconds`; the clip playing now keeps
  // running underneath until the fade ends.
  void crossFade(const Clip& clip, double seconds, LoopMode mode = LoopMode::Repeat);

  // Advances by dt * speed (the fade advances by |dt|: it is wall time).
  void update(double dt);
  void seek(double time) { current_.time = time; }
  void setSpeed(double speed) { speed_ = speed; }
  double speed() const { return speed_; }
  double time() const { return current_.time; }  // unwrapped playhead
  double localTime() const;                        // wrapped into the clip
  // Weight of the current clip: rises from 0 to 1 during a cross-fade.
  float fadeWeight() const;
  const Clip* clip() const { return current_.clip; }

  // Writes the blended local pose (one Srt per joint) and, when `morphWeights` is
  // not empty, the blended morph weights (MorphLayout order). False without a
  // clip or with a span of the wrong size.
  bool evaluate(std::span<Srt> locals, std::span<float> morphWeights = {});

 private:
  // A clip playing, with its key cursors (kept with the layer when a fade moves
  // it from current to previous, so neither restarts its search).
  struct Layer {
    const Clip* clip = nullptr;
    LoopMode mode = LoopMode::Repeat;
    double time = 0.0;
    SamplingContext context;
  };
  void start(Layer& layer, const Clip& clip, LoopMode mode);

  const Skeleton* skeleton_;
  Layer current_;
  Layer previous_;
  double fadeSeconds_ = 0.0;
  double fadeElapsed_ = 0.0;
  double speed_ = 1.0;
  bool evaluateMorphs(std::span<float> weights);

  std::vector<Srt> currentPose_;
  std::vector<Srt> previousPose_;
  std::vector<float> restWeights_;
  std::vector<float> currentWeights_;
  std::vector<float> previousWeights_;
};

}  // namespace engine
