#include "anim/player.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "anim/jobs.h"

namespace engine {

std::optional<LoopMode> parseLoopMode(std::string_view text) {
  if (text == "repeat") return LoopMode::Repeat;
  if (text == "clamp") return LoopMode::Clamp;
  if (text == "pingpong") return LoopMode::PingPong;
  return std::nullopt;
}

double wrapTime(double time, double duration, LoopMode mode) {
  if (!(duration > 0.0) || !std::isfinite(time)) return 0.0;
  switch (mode) {
    case LoopMode::Clamp: return std::clamp(time, 0.0, duration);
    case LoopMode::PingPong: {
      double t = time - 2.0 * duration * std::floor(time / (2.0 * duration));
      return t <= duration ? t : 2.0 * duration - t;
    }
    case LoopMode::Repeat: break;
  }
  double t = time - duration * std::floor(time / duration);
  // Rounding can land exactly on D for a t just below a multiple of D; D wraps to 0.
  return t >= duration ? 0.0 : t;
}

Player::Player(const Skeleton& skeleton, std::span<const float> restMorphWeights)
    : skeleton_(&skeleton),
      currentPose_(static_cast<std::size_t>(skeleton.jointCount())),
      previousPose_(static_cast<std::size_t>(skeleton.jointCount())),
      restWeights_(restMorphWeights.begin(), restMorphWeights.end()),
      currentWeights_(restMorphWeights.size()),
      previousWeights_(restMorphWeights.size()) {}

void Player::start(Layer& layer, const Clip& clip, LoopMode mode) {
  layer.clip = &clip;
  layer.mode = mode;
  layer.time = 0.0;
  layer.context.bind(clip);
}

void Player::play(const Clip& clip, LoopMode mode) {
  start(current_, clip, mode);
  previous_.clip = nullptr;
  fadeSeconds_ = fadeElapsed_ = 0.0;
}

void Player::crossFade(const Clip& clip, double seconds, LoopMode mode) {
  if (current_.clip == nullptr || !(seconds > 0.0)) {
    play(clip, mode);
    return;
  }
  std::swap(previous_, current_);
  start(current_, clip, mode);
  fadeSeconds_ = seconds;
  fadeElapsed_ = 0.0;
}

void Player::update(double dt) {
  if (!std::isfinite(dt)) return;
  current_.time += dt * speed_;
  if (previous_.clip == nullptr) return;
  previous_.time += dt * speed_;
  fadeElapsed_ += std::abs(dt);
  if (fadeElapsed_ >= fadeSeconds_) previous_.clip = nullptr;
}

double Player::localTime() const {
  if (current_.clip == nullptr) return 0.0;
  return wrapTime(current_.time, current_.clip->duration(), current_.mode);
}

float Player::fadeWeight() const {
  if (previous_.clip == nullptr) return 1.0f;
  return static_cast<float>(std::clamp(fadeElapsed_ / fadeSeconds_, 0.0, 1.0));
}

bool Player::evaluate(std::span<Srt> locals, std::span<float> morphWeights) {
  if (current_.clip == nullptr || locals.size() != currentPose_.size()) return false;
  if (!morphWeights.empty() && !evaluateMorphs(morphWeights)) return false;
  SamplingJob sample{current_.clip, localTime(), skeleton_->restPose(), locals};
  sample.context = &current_.context;
  if (previous_.clip == nullptr) return sample.run();
  sample.output = currentPose_;
  SamplingJob before{previous_.clip, wrapTime(previous_.time, previous_.clip->duration(), previous_.mode),
                     skeleton_->restPose(), previousPose_};
  before.context = &previous_.context;
  if (!sample.run() || !before.run()) return false;
  float w = fadeWeight();
  std::array<BlendingJob::Layer, 2> layers{{{previousPose_, 1.0f - w}, {currentPose_, w}}};
  BlendingJob blend{layers, skeleton_->restPose(), locals};
  return blend.run();
}

// The same cross-fade as the pose, on the morph weights.
bool Player::evaluateMorphs(std::span<float> weights) {
  if (weights.size() != restWeights_.size()) return false;
  MorphSamplingJob sample{current_.clip, localTime(), restWeights_, weights, &current_.context};
  if (previous_.clip == nullptr) return sample.run();
  sample.output = currentWeights_;
  MorphSamplingJob before{previous_.clip, wrapTime(previous_.time, previous_.clip->duration(), previous_.mode),
                          restWeights_, previousWeights_, &previous_.context};
  if (!sample.run() || !before.run()) return false;
  const float w = fadeWeight();
  std::array<MorphBlendingJob::Layer, 2> layers{{{previousWeights_, 1.0f - w}, {currentWeights_, w}}};
  return MorphBlendingJob{layers, restWeights_, weights}.run();
}

}  // namespace engine
