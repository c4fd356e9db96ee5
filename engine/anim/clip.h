#pragma once
// Keyframed animation of a skeleton's local transforms, and its sampling.
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "anim/skeleton.h"
#include "core/keyframe.h"
#include "core/math.h"
#include "core/result.h"

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
};

// The morph target weights of one mesh node: `targets` weights per key (three
// blocks of `targets` per key for CubicSpline: in-tangents, values, out-tangents,
// as glTF stores them).
struct MorphTrack {
  int node = -1;   // RawSkeleton index (glTF node)
  int first = -1;  // set by Clip::build: where the node's weights start (MorphLayout)
  int targets = 0;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;
  std::vector<float> values;
};

// Where each node's morph weights live in one flat array per model instance, so
// that sampling, blending, skinning and the GPU upload share one buffer: node n
// with N targets owns [first[n], first[n] + N).
struct MorphLayout {
  std::vector<int> first;          // per RawSkeleton index; -1 without targets
  std::vector<int> targets;        // per RawSkeleton index; 0 without targets
  std::vector<float> restWeights;  // the default weights, flat
  std::size_t size() const { return restWeights.size(); }
  // The weights of `node` in a flat array laid out like this one; empty for a
  // node without targets.
  std::span<const float> of(std::span<const float> weights, int node) const;
};

// Offline clip: tracks name joints (and morph tracks nodes) by RawSkeleton index.
struct RawClip {
  std::string name;
  std::vector<Track> tracks;
  std::vector<MorphTrack> morphTracks;
};

class Clip {
 public:
  // Validates every track (keys sorted, finite, >= 0; value counts match) and
  // maps joints to runtime indices and morph tracks to their place in `morphs`
  // (a morph track of a node without that many targets is an error). Rotation
  // keys of Step/Linear tracks are normalised so that interpolation starts from
  // true rotations.
  static Result<Clip> build(const RawClip& raw, const Skeleton& skeleton, const MorphLayout& morphs = {});

  const std::string& name() const { return name_; }
  // Largest last key time of any track (three.js AnimationClip.duration): the
  // period of a repeating clip. Zero for a clip without keys past 0.
  double duration() const { return duration_; }
  std::span<const Track> tracks() const { return tracks_; }
  std::span<const MorphTrack> morphTracks() const { return morphTracks_; }

 private:
  std::string name_;
  double duration_ = 0.0;
  std::vector<Track> tracks_;
  std::vector<MorphTrack> morphTracks_;
};

// Value of a track at clip-local `time`: the first value before the first key,
// the last after the last key; O(log keys).
// How LINEAR rotation keys are interpolated: slerp is exact (constant angular
// speed); nlerp is the cheaper shortcut whose error the benchmarks measure.
enum class QuatInterpolation { Slerp, Nlerp };

glm::vec3 sampleVec3(const Track& track, double time);
// Rotations take the shortest arc between two keys, CUBICSPLINE ones included (the
// second key's value and in-tangent are negated into the first's hemisphere).
glm::quat sampleQuat(const Track& track, double time,
                     QuatInterpolation method = QuatInterpolation::Slerp);  // unit length

// Writes the track's `targets` weights at `time` into `out` (out.size() must be
// track.targets), held like sampleVec3 outside the keys.
void sampleWeights(const MorphTrack& track, double time, std::span<float> out);

// Writes the track's value at `time` into the matching part of `srt`.
void applyTrack(const Track& track, double time, Srt& srt,
                QuatInterpolation method = QuatInterpolation::Slerp);

}  // namespace engine
