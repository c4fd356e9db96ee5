#pragma once
// Keyframed animation of a skeleton's local transforms, and its sampling.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "anim/key_blocks.h"
#include "anim/skeleton.h"
#include "anim/track.h"
#include "core/keyframe.h"
#include "core/math.h"
#include "core/result.h"

namespace engine {

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
  // The distinct key times of the tracks: glTF exporters give most channels of an
  // animation one input accessor, so a cursor per timeline finds the keys of many
  // tracks at once.
  std::span<const std::vector<float>> timelines() const { return timelines_; }
  // Unique to each built clip (copies share it, having the same keys): what a
  // SamplingContext recognises its clip by, as an address can be reused.
  std::uint64_t id() const { return id_; }
  // The tracks as sampleTracks walks them: the LINEAR ones of each timeline in
  // KeyBlocks (indexed as timelines()), the rest (STEP, CUBICSPLINE) by index. Empty
  // when two tracks drive the same part of one joint (glTF forbids it): such a clip
  // is sampled track by track, in order, as the last track must win.
  std::span<const KeyBlocks> linearBlocks() const { return blocks_; }
  std::span<const std::uint32_t> otherTracks() const { return others_; }
  bool grouped() const { return grouped_; }
  // Grouped clips: the joints below jointsDriven() with a part (translation,
  // rotation or scale) that no track drives, which keeps its rest value. Every part
  // of the other joints below it is written by sampleTracks, so a sampler need not
  // copy their rest pose first.
  std::span<const std::uint32_t> partlyDrivenJoints() const { return partlyDriven_; }
  // 1 + the largest joint a track drives (0 without tracks).
  std::size_t jointsDriven() const { return jointsDriven_; }

 private:
  int timelineOf(const std::vector<float>& times);  // adds `times` when new
  void groupTracks();

  std::string name_;
  std::uint64_t id_ = 0;
  double duration_ = 0.0;
  std::vector<std::vector<float>> timelines_;
  std::vector<KeyBlocks> blocks_;
  std::vector<std::uint32_t> others_;
  std::vector<std::uint32_t> partlyDriven_;
  bool grouped_ = false;
  std::size_t jointsDriven_ = 0;
  std::vector<Track> tracks_;
  std::vector<MorphTrack> morphTracks_;
};

// Where a timeline found its keys last time: the index of the first key after
// the time it sampled (0 to start with). Sampling with a cursor gives exactly the
// result of sampling without one, whatever the cursor holds; a time a few keys
// past the last one finds its keys in a step or two instead of a binary search,
// an earlier one or a later one searches.
using KeyCursor = std::uint32_t;

// Value of a track at clip-local `time`: the first value before the first key,
// the last after the last key; O(log keys) (sampleTracks with a SamplingContext
// finds the keys in O(1) during playback).
glm::vec3 sampleVec3(const Track& track, double time);
// Rotations take the shortest arc between two keys, CUBICSPLINE ones included (the
// second key's value and in-tangent are negated into the first's hemisphere).
glm::quat sampleQuat(const Track& track, double time,
                     QuatInterpolation method = QuatInterpolation::Slerp);  // unit length

// Writes the track's `targets` weights at `time` into `out` (out.size() must be
// track.targets), held like sampleVec3 outside the keys.
void sampleWeights(const MorphTrack& track, double time, std::span<float> out);
void sampleWeights(const MorphTrack& track, double time, std::span<float> out, KeyCursor& cursor);

// What one character's playback of one clip keeps between frames (ozz's
// SamplingJob::Context): a key cursor per timeline and per morph track. Owned by
// the caller, one per character instance and clip it plays; forward playback then
// finds its keys in O(1) amortised; seeks back or far ahead search. Results never
// depend on what it holds: a context used with another clip is reset to it (the
// only time it allocates: when the clip needs more room than any before).
class SamplingContext {
 public:
  // Resets the context to `clip` unless it already serves it.
  void bind(const Clip& clip);
  std::span<KeyCursor> timelineCursors() { return timelines_; }
  std::span<KeyPair> timelineKeys() { return keys_; }
  std::span<KeyCursor> morphCursors() { return morphTracks_; }

 private:
  std::uint64_t clip_ = 0;  // Clip::id(); 0 is no clip's
  std::vector<KeyCursor> timelines_, morphTracks_;
  std::vector<KeyPair> keys_;
};

// Writes every track of `clip` at `time` into `output` (indexed by joint), the
// same values as applyTrack of each track, finding keys through `context`.
void sampleTracks(const Clip& clip, double time, std::span<Srt> output, QuatInterpolation method,
                  SamplingContext& context);

// Writes the track's value at `time` into the matching part of `srt`.
void applyTrack(const Track& track, double time, Srt& srt,
                QuatInterpolation method = QuatInterpolation::Slerp);

}  // namespace engine
