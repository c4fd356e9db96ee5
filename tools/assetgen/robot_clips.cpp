#include "robot_clips.h"

#include <cassert>
#include <cmath>
#include <functional>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "robot_rig.h"

namespace assetgen {

namespace {

using engine::AnimPath;
using engine::Interpolation;

// Angles in degrees about X (positive tips +Y towards +Z: a hanging limb swings
// back), Y (positive turns +Z towards +X) and Z (positive turns +X towards +Y).
using Euler = glm::dvec3;
using PoseFn = std::function<Euler(double t)>;
using OffsetFn = std::function<glm::dvec3(double t)>;

constexpr double kTwoPi = glm::two_pi<double>();

double smoothstep(double edge0, double edge1, double x) {
  const double t = glm::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Channel makeChannel(int joint, AnimPath path, Interpolation interpolation) {
  Channel channel;
  channel.joint = joint;
  channel.path = path;
  channel.interpolation = interpolation;
  return channel;
}

Clip makeClip(const char* name, double duration) {
  Clip clip;
  clip.name = name;
  clip.duration = static_cast<float>(duration);
  return clip;
}

std::vector<float> keyTimes(double duration, int keys) {
  std::vector<float> times;
  for (int i = 0; i < keys; ++i) {
    times.push_back(static_cast<float>(duration * i / (keys - 1)));
  }
  return times;
}

glm::vec4 rotationKey(const Euler& degrees) {
  const glm::dquat q = glm::normalize(glm::dquat(glm::radians(degrees)));
  return {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z),
          static_cast<float>(q.w)};
}

// The loop closes on the very same bytes: the sampled last key only has to agree
// with the first to rounding, then the first is copied over it.
void closeLoop(std::vector<glm::vec4>& values) {
  assert(glm::length(values.back() - values.front()) < 1e-5f);
  values.back() = values.front();
}

// A LINEAR rotation track sampled from `pose` at `keys` even steps over the clip.
Channel rotationTrack(int joint, double duration, int keys, const PoseFn& pose) {
  Channel channel = makeChannel(joint, AnimPath::Rotation, Interpolation::Linear);
  channel.times = keyTimes(duration, keys);
  for (float t : channel.times) {
    glm::vec4 q = rotationKey(pose(t));
    // Neighbouring keys in the same hemisphere, so interpolation takes the short way.
    if (!channel.values.empty() && glm::dot(q, channel.values.back()) < 0.0f) q = -q;
    channel.values.push_back(q);
  }
  closeLoop(channel.values);
  return channel;
}

// A LINEAR translation track: the joint's bind translation plus `offset`.
Channel translationTrack(int joint, glm::vec3 bind, double duration, int keys,
                         const OffsetFn& offset) {
  Channel channel = makeChannel(joint, AnimPath::Translation, Interpolation::Linear);
  channel.times = keyTimes(duration, keys);
  for (float t : channel.times) {
    channel.values.push_back(glm::vec4(glm::vec3(glm::dvec3(bind) + offset(t)), 0.0f));
  }
  closeLoop(channel.values);
  return channel;
}

// A CUBICSPLINE translation track: values and their exact time derivatives, so the
// curve between the sparse keys follows the function itself.
Channel cubicTranslationTrack(int joint, glm::vec3 bind, double duration, int keys,
                              const OffsetFn& offset, const OffsetFn& velocity) {
  Channel channel = makeChannel(joint, AnimPath::Translation, Interpolation::CubicSpline);
  channel.times = keyTimes(duration, keys);
  for (float t : channel.times) {
    const glm::vec4 tangent(glm::vec3(velocity(t)), 0.0f);
    channel.values.push_back(tangent);
    channel.values.push_back(glm::vec4(glm::vec3(glm::dvec3(bind) + offset(t)), 0.0f));
    channel.values.push_back(tangent);
  }
  const size_t n = channel.values.size();
  for (size_t i = 0; i < 3; ++i) {
    assert(glm::length(channel.values[n - 3 + i] - channel.values[i]) < 1e-5f);
    channel.values[n - 3 + i] = channel.values[i];
  }
  return channel;
}

// A STEP rotation track: the pose jumps at each key, as a robot's servo would.
Channel stepRotationTrack(int joint, const std::vector<float>& times,
                          const std::vector<Euler>& poses) {
  Channel channel = makeChannel(joint, AnimPath::Rotation, Interpolation::Step);
  channel.times = times;
  for (const Euler& pose : poses) channel.values.push_back(rotationKey(pose));
  closeLoop(channel.values);
  return channel;
}

Clip walk(const std::vector<Joint>& skeleton) {
  constexpr double kDuration = 1.0;
  constexpr int kKeys = 31;
  Clip clip = makeClip("Walk", kDuration);
  // One stride of each leg per loop: the left leg is fully forward at a quarter.
  const auto phase = [](double t) { return kTwoPi * t / kDuration; };
  const auto thigh = [&](double p) { return -20.0 * std::sin(p) - 3.0; };
  // The knee folds most while the leg swings through (thigh moving forward).
  const auto knee = [&](double p) { return 5.0 + 45.0 * std::pow(0.5 + 0.5 * std::cos(p), 3.0); };
  // The foot cancels most of the leg's pitch so the sole stays near level.
  const auto foot = [&](double p) { return -0.85 * (thigh(p) + knee(p)); };
  const auto elbow = [&](double p) { return -(12.0 + 18.0 * (0.5 - 0.5 * std::sin(p))); };

  auto& c = clip.channels;
  // The pelvis drops as far as the spread legs shorten, so the feet stay near the
  // ground, and sways over the standing foot.
  c.push_back(
      translationTrack(kPelvis, skeleton[kPelvis].bindPosition, kDuration, kKeys, [&](double t) {
        const double p = phase(t);
        return glm::dvec3(0.012 * std::sin(p), -0.0175 + 0.0175 * std::cos(2.0 * p), 0.0);
      }));
  c.push_back(rotationTrack(kPelvis, kDuration, kKeys, [&](double t) {
    return Euler(0.0, -5.0 * std::sin(phase(t)), 2.0 * std::cos(phase(t)));
  }));
  c.push_back(rotationTrack(kSpine, kDuration, kKeys, [&](double t) {
    return Euler(1.5, 3.0 * std::sin(phase(t)), -1.0 * std::cos(phase(t)));
  }));
  c.push_back(rotationTrack(kChest, kDuration, kKeys, [&](double t) {
    return Euler(2.0 + std::cos(2.0 * phase(t)), 4.0 * std::sin(phase(t)), 0.0);
  }));
  c.push_back(rotationTrack(kHead, kDuration, kKeys,
                            [&](double t) { return Euler(-3.5, -2.0 * std::sin(phase(t)), 0.0); }));
  for (int side = 0; side < 2; ++side) {
    // The right side runs half a cycle behind the left; arms swing against the legs.
    const double shift = side == 0 ? 0.0 : glm::pi<double>();
    const double outward = side == 0 ? 1.0 : -1.0;
    const int upperArm = side == 0 ? kUpperArmL : kUpperArmR;
    const int thighJoint = side == 0 ? kThighL : kThighR;
    c.push_back(rotationTrack(thighJoint, kDuration, kKeys, [&, shift](double t) {
      return Euler(thigh(phase(t) + shift), 0.0, 0.0);
    }));
    c.push_back(rotationTrack(thighJoint + 1, kDuration, kKeys, [&, shift](double t) {
      return Euler(knee(phase(t) + shift), 0.0, 0.0);
    }));
    c.push_back(rotationTrack(thighJoint + 2, kDuration, kKeys, [&, shift](double t) {
      return Euler(foot(phase(t) + shift), 0.0, 0.0);
    }));
    c.push_back(rotationTrack(upperArm, kDuration, kKeys, [&, shift, outward](double t) {
      return Euler(18.0 * std::sin(phase(t) + shift), 0.0, 6.0 * outward);
    }));
    c.push_back(rotationTrack(upperArm + 1, kDuration, kKeys, [&, shift](double t) {
      return Euler(elbow(phase(t) + shift), 0.0, 0.0);
    }));
  }
  return clip;
}

// Standing: two slow breaths, a gentle sway, and the head snapping between looks.
Clip idle(const std::vector<Joint>& skeleton) {
  constexpr double kDuration = 2.0;
  constexpr int kKeys = 41;
  Clip clip = makeClip("Idle", kDuration);
  constexpr double kRate = kTwoPi / kDuration;
  const auto phase = [](double t) { return kRate * t; };
  auto& c = clip.channels;
  c.push_back(cubicTranslationTrack(
      kPelvis, skeleton[kPelvis].bindPosition, kDuration, 9,
      [&](double t) {
        const double p = phase(t);
        return glm::dvec3(0.008 * std::sin(p), -0.004 + 0.004 * std::cos(2.0 * p), 0.0);
      },
      [&](double t) {
        const double p = phase(t);
        return glm::dvec3(0.008 * kRate * std::cos(p), -0.008 * kRate * std::sin(2.0 * p), 0.0);
      }));
  c.push_back(rotationTrack(kSpine, kDuration, kKeys, [&](double t) {
    return Euler(1.0 * std::sin(phase(t)), 0.0, -1.5 * std::sin(phase(t)));
  }));
  c.push_back(rotationTrack(kChest, kDuration, kKeys, [&](double t) {
    return Euler(-1.5 * std::sin(2.0 * phase(t)), 1.5 * std::sin(phase(t)), 0.0);
  }));
  c.push_back(rotationTrack(kNeck, kDuration, kKeys, [&](double t) {
    return Euler(1.0 * std::sin(2.0 * phase(t) + 1.0) - 1.0 * std::sin(1.0), 0.0, 0.0);
  }));
  c.push_back(stepRotationTrack(
      kHead, keyTimes(kDuration, 5),
      {Euler(0.0), Euler(0.0, 15.0, 0.0), Euler(0.0), Euler(-4.0, -15.0, 0.0), Euler(0.0)}));
  for (int side = 0; side < 2; ++side) {
    const double outward = side == 0 ? 1.0 : -1.0;
    const int upperArm = side == 0 ? kUpperArmL : kUpperArmR;
    c.push_back(rotationTrack(upperArm, kDuration, kKeys, [&, outward](double t) {
      return Euler(2.0 * outward * std::sin(phase(t)), 0.0,
                   outward * (4.0 + 2.0 * std::sin(2.0 * phase(t))));
    }));
    c.push_back(rotationTrack(upperArm + 1, kDuration, kKeys, [&](double t) {
      return Euler(-8.0 - 3.0 * std::sin(2.0 * phase(t)), 0.0, 0.0);
    }));
  }
  return clip;
}

// From the rest pose the right arm rises, the forearm waves twice and the arm comes
// back down, so the clip starts and ends at rest.
Clip wave() {
  constexpr double kDuration = 1.5;
  constexpr int kKeys = 46;
  constexpr double kRaise = 0.35, kLower = 1.15, kWaves = 2.0;
  Clip clip = makeClip("Wave", kDuration);
  const auto raised = [](double t) {
    return smoothstep(0.0, kRaise, t) * (1.0 - smoothstep(kLower, kDuration, t));
  };
  const auto sway = [](double t) {
    if (t <= kRaise || t >= kLower) return 0.0;
    return std::sin(kTwoPi * kWaves * (t - kRaise) / (kLower - kRaise));
  };
  auto& c = clip.channels;
  c.push_back(rotationTrack(kChest, kDuration, kKeys, [&](double t) {
    return Euler(0.0, -4.0 * raised(t), -3.0 * raised(t));
  }));
  c.push_back(rotationTrack(kHead, kDuration, kKeys, [&](double t) {
    return Euler(-3.0 * raised(t), -10.0 * raised(t), 6.0 * raised(t) + 2.0 * sway(t));
  }));
  c.push_back(rotationTrack(kUpperArmR, kDuration, kKeys, [&](double t) {
    return Euler(-10.0 * raised(t), 0.0, -140.0 * raised(t));
  }));
  c.push_back(rotationTrack(kLowerArmR, kDuration, kKeys, [&](double t) {
    return Euler(0.0, 0.0, -20.0 * raised(t) + 30.0 * sway(t));
  }));
  c.push_back(rotationTrack(kHandR, kDuration, kKeys,
                            [&](double t) { return Euler(0.0, 0.0, 12.0 * sway(t)); }));
  c.push_back(rotationTrack(kUpperArmL, kDuration, kKeys, [&](double t) {
    return Euler(-3.0 * raised(t), 0.0, 3.0 * raised(t));
  }));
  return clip;
}

}  // namespace

std::vector<Clip> robotClips(const std::vector<Joint>& skeleton) {
  return {idle(skeleton), walk(skeleton), wave()};
}

}  // namespace assetgen
