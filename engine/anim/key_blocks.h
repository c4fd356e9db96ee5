#pragma once
// The LINEAR tracks of one timeline laid out for playback (after ozz-animation's SoA
// sampling): for each interval between two consecutive keys, every track's first
// key and what the second adds, in lanes of four tracks. A frame finds its interval
// once per timeline and interpolates four tracks at a time with that timeline's one
// u, reading contiguous floats instead of each track's keys. Built with the clip and
// shared by every character that plays it.
//
// It gives the bits of interpolating track by track (lerp, nlerp, slerpAt): the
// same float operations in the same order, lane by lane. Its size: 6 floats per
// translation or scale and 10 per rotation, per interval, in lanes of four: about
// twice the keys' own, three times for rotations.
#include <cstdint>
#include <span>
#include <vector>

#include "anim/track.h"
#include "core/math.h"

namespace engine {

class KeyBlocks {
 public:
  KeyBlocks() = default;
  // `linear`: the indices in `tracks` of the LINEAR tracks on one timeline of
  // `keys` keys, at most one per joint and path.
  KeyBlocks(std::span<const Track> tracks, std::span<const std::uint32_t> linear, std::size_t keys);

  // The tracks it holds (indices in the clip's tracks), in the order given.
  std::span<const std::uint32_t> tracks() const { return tracks_; }
  // Writes every track's value between the keys of `k` (k.first < k.second) into
  // its joint's part of `output`.
  void sample(const KeyPair& k, QuatInterpolation method, std::span<Srt> output) const;

 private:
  // One path's tracks: their joints, and where their floats start in an interval.
  struct Group {
    std::vector<std::uint32_t> joints;
    std::size_t lanes = 0;   // joints.size() rounded up to four
    std::size_t offset = 0;  // in floats, from the interval's start
  };
  void fillVec3(std::span<const Track> tracks, std::span<const std::uint32_t> ids, const Group& group,
                std::size_t interval);
  void fillRotations(std::span<const Track> tracks, std::span<const std::uint32_t> ids, std::size_t interval);

  std::vector<std::uint32_t> tracks_;
  Group translations_, scales_, rotations_;
  std::size_t stride_ = 0;  // floats per interval
  std::vector<float> data_;
};

}  // namespace engine
