#pragma once
// One animated part of one joint, and the key pair a time falls between: what a
// clip is made of and what its sampling layouts (clip.h, key_blocks.h) read.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/keyframe.h"

namespace engine {

// One animated part of one joint. `values` has one entry per key (three for
// CubicSpline: in-tangent, value, out-tangent); translation and scale use xyz,
// rotation is x, y, z, w as in glTF.
struct Track {
  int joint = -1;
  AnimPath path = AnimPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;
  std::vector<glm::vec4> values;
  int timeline = -1;  // set by Clip::build: the index of `times` in Clip::timelines()
};

// A rotation key as a quaternion (values hold x, y, z, w; glm takes w first).
inline glm::quat toQuat(const glm::vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); }

// How LINEAR rotation keys are interpolated: slerp is exact (constant angular
// speed); nlerp is the cheaper shortcut whose error the benchmarks measure.
enum class QuatInterpolation { Slerp, Nlerp };

// The keys around a time: first == second outside the keys, where the nearest end
// value is held.
struct KeyPair {
  std::size_t first = 0;
  std::size_t second = 0;
  float u = 0.0f;  // 0 at first, 1 at second
  double interval = 0.0;
};

}  // namespace engine
