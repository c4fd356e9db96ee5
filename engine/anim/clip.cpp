#include "anim/clip.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace engine {
namespace {

// Key times, for joint and morph tracks alike: at least one, finite, >= 0, sorted.
Status validateTimes(const std::vector<float>& times, const std::string& name) {
  if (times.empty()) return makeError(name + ": has no keys");
  for (std::size_t k = 0; k < times.size(); ++k) {
    float t = times[k];
    if (!std::isfinite(t) || t < 0.0f || (k > 0 && t < times[k - 1]))
      return makeError(name + ": key " + std::to_string(k) + " time is NaN, negative or unsorted");
  }
  return Ok{};
}

std::size_t valuesPerKey(Interpolation interpolation) { return interpolation == Interpolation::CubicSpline ? 3 : 1; }

Status validateTrack(const Track& track, std::size_t index, int rawJointCount) {
  std::string name = "track " + std::to_string(index);
  if (track.joint < 0 || track.joint >= rawJointCount)
    return makeError(name + ": joint " + std::to_string(track.joint) + " does not exist");
  if (track.times.empty()) return makeError(name + ": has no keys");
  if (track.values.size() != track.times.size() * valuesPerKey(track.interpolation))
    return makeError(name + ": " + std::to_string(track.values.size()) + " values for " +
                     std::to_string(track.times.size()) + " keys");
  if (Status s = validateTimes(track.times, name); !s) return s;
  for (std::size_t v = 0; v < track.values.size(); ++v) {
    const glm::vec4& x = track.values[v];
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z) || !std::isfinite(x.w))
      return makeError(name + ": value " + std::to_string(v) + " is NaN or infinite");
  }
  return Ok{};
}

// A morph track must drive exactly the targets its node has in `morphs`.
Status validateMorphTrack(const MorphTrack& track, std::size_t index, const MorphLayout& morphs) {
  std::string name = "morph track " + std::to_string(index);
  const bool known = track.node >= 0 && static_cast<std::size_t>(track.node) < morphs.targets.size();
  const int targets = known ? morphs.targets[static_cast<std::size_t>(track.node)] : 0;
  if (targets == 0) return makeError(name + ": node " + std::to_string(track.node) + " has no morph targets");
  if (track.targets != targets)
    return makeError(name + ": " + std::to_string(track.targets) + " weights per key, node " +
                     std::to_string(track.node) + " has " + std::to_string(targets) + " morph targets");
  if (Status s = validateTimes(track.times, name); !s) return s;
  const std::size_t expected = track.times.size() * valuesPerKey(track.interpolation) * std::size_t(targets);
  if (track.values.size() != expected)
    return makeError(name + ": " + std::to_string(track.values.size()) + " weights for " +
                     std::to_string(track.times.size()) + " keys of " + std::to_string(targets) + " targets");
  for (std::size_t v = 0; v < track.values.size(); ++v)
    if (!std::isfinite(track.values[v])) return makeError(name + ": weight " + std::to_string(v) + " is NaN or infinite");
  return Ok{};
}

// The first key after `time` in [first, last): std::upper_bound, comparing in double.
std::size_t keyAfter(const std::vector<float>& times, double time, std::size_t first, std::size_t last) {
  auto it = std::upper_bound(times.begin() + std::ptrdiff_t(first), times.begin() + std::ptrdiff_t(last), time,
                             [](double t, float key) { return t < static_cast<double>(key); });
  return static_cast<std::size_t>(it - times.begin());
}

// Keys a cursor steps over before it searches instead: forward playback at 60 Hz
// over keys at 24-30 Hz moves by 0 or 1 key a frame.
constexpr std::size_t kCursorSteps = 4;

// The same index as keyAfter over all keys (it is unique: the first key greater
// than `time` in a sorted array), found from the cursor's last one: a few steps
// forward, else a search of the keys past it, or of those before it when time went
// back.
std::size_t keyAfter(const std::vector<float>& times, double time, KeyCursor& cursor) {
  const std::size_t n = times.size();
  std::size_t i = std::min<std::size_t>(cursor, n);
  if (i > 0 && time < static_cast<double>(times[i - 1])) {
    i = keyAfter(times, time, 0, i - 1);
  } else {
    const std::size_t stop = std::min(n, i + kCursorSteps);
    while (i < stop && !(time < static_cast<double>(times[i]))) ++i;
    if (i == stop && i < n && !(time < static_cast<double>(times[i]))) i = keyAfter(times, time, i + 1, n);
  }
  cursor = static_cast<KeyCursor>(i);
  return i;
}

// The key pair around `time` given i, the first key after it.
KeyPair keysBefore(const std::vector<float>& times, double time, std::size_t i) {
  if (i == 0) return {};
  if (i == times.size()) return {i - 1, i - 1, 0.0f, 0.0};
  // upper_bound skips equal times, so t0 < t1 and the division is safe.
  double t0 = times[i - 1], t1 = times[i];
  return {i - 1, i, static_cast<float>((time - t0) / (t1 - t0)), t1 - t0};
}

KeyPair findKeys(const std::vector<float>& times, double time) {
  return keysBefore(times, time, keyAfter(times, time, 0, times.size()));
}

KeyPair findKeys(const std::vector<float>& times, double time, KeyCursor& cursor) {
  return keysBefore(times, time, keyAfter(times, time, cursor));
}

// glTF cubic Hermite: p(s) = h00 v0 + h10 dt b0 + h01 v1 + h11 dt a1, tangents
// per second, so they scale with the key interval. One basis for vectors and
// morph weights alike.
struct HermiteBasis {
  float value0, outTangent0, value1, inTangent1;
  explicit HermiteBasis(const KeyPair& keys) {
    float s = keys.u, s2 = s * s, s3 = s2 * s;
    float dt = static_cast<float>(keys.interval);
    value0 = 2 * s3 - 3 * s2 + 1;
    outTangent0 = (s3 - 2 * s2 + s) * dt;
    value1 = -2 * s3 + 3 * s2;
    inTangent1 = (s3 - s2) * dt;
  }
};

// sign1 multiplies the second key's value and in-tangent (see hermiteQuat).
glm::vec4 hermite(const Track& track, const KeyPair& keys, float sign1 = 1.0f) {
  const HermiteBasis h(keys);
  const glm::vec4& v0 = track.values[keys.first * 3 + 1];
  const glm::vec4& b0 = track.values[keys.first * 3 + 2];
  const glm::vec4 a1 = track.values[keys.second * 3] * sign1;
  const glm::vec4 v1 = track.values[keys.second * 3 + 1] * sign1;
  return h.value0 * v0 + h.outTangent0 * b0 + h.value1 * v1 + h.inTangent1 * a1;
}

// A CUBICSPLINE rotation. Keys in opposite hemispheres (q and -q are one rotation)
// would send the curve through zero, where it has no direction and its rounding
// noise becomes the rotation; so the second key, value and in-tangent, is negated
// into the first's hemisphere, as LINEAR's shortest arc does (glTF leaves the sign
// open; for keys already in one hemisphere nothing changes). Tangents can still
// carry the curve through zero: the keys' nlerp is then the nearest rotation,
// where safeNormalize would snap the joint to identity.
glm::quat hermiteQuat(const Track& track, const KeyPair& keys) {
  glm::quat q0 = toQuat(track.values[keys.first * 3 + 1]), q1 = toQuat(track.values[keys.second * 3 + 1]);
  glm::quat q = toQuat(hermite(track, keys, glm::dot(q0, q1) < 0.0f ? -1.0f : 1.0f));
  return hasDirection(q) ? safeNormalize(q) : nlerp(q0, q1, keys.u);
}

std::size_t valueIndex(const Track& track, std::size_t key) {
  return track.interpolation == Interpolation::CubicSpline ? key * 3 + 1 : key;
}

}  // namespace

std::span<const float> MorphLayout::of(std::span<const float> weights, int node) const {
  if (node < 0 || static_cast<std::size_t>(node) >= first.size() || first[static_cast<std::size_t>(node)] < 0) return {};
  return weights.subspan(static_cast<std::size_t>(first[static_cast<std::size_t>(node)]),
                         static_cast<std::size_t>(targets[static_cast<std::size_t>(node)]));
}

Result<Clip> Clip::build(const RawClip& raw, const Skeleton& skeleton, const MorphLayout& morphs) {
  static std::atomic<std::uint64_t> lastId{0};
  Clip clip;
  clip.name_ = raw.name;
  clip.id_ = ++lastId;
  std::string prefix = "clip \"" + raw.name + "\": ";
  for (std::size_t i = 0; i < raw.tracks.size(); ++i) {
    if (Status s = validateTrack(raw.tracks[i], i, skeleton.jointCount()); !s)
      return makeError(prefix + s.error().message);
    Track track = raw.tracks[i];
    track.joint = skeleton.jointOfRaw(track.joint);
    if (track.path == AnimPath::Rotation && track.interpolation != Interpolation::CubicSpline)
      for (glm::vec4& v : track.values) {
        glm::quat q = safeNormalize(toQuat(v));
        v = glm::vec4(q.x, q.y, q.z, q.w);
      }
    clip.duration_ = std::max(clip.duration_, static_cast<double>(track.times.back()));
    track.timeline = clip.timelineOf(track.times);
    clip.tracks_.push_back(std::move(track));
  }
  clip.groupTracks();
  for (std::size_t i = 0; i < raw.morphTracks.size(); ++i) {
    if (Status s = validateMorphTrack(raw.morphTracks[i], i, morphs); !s) return makeError(prefix + s.error().message);
    MorphTrack track = raw.morphTracks[i];
    track.first = morphs.first[static_cast<std::size_t>(track.node)];
    clip.duration_ = std::max(clip.duration_, static_cast<double>(track.times.back()));
    clip.morphTracks_.push_back(std::move(track));
  }
  return clip;
}

namespace {

glm::vec3 vec3At(const Track& track, const KeyPair& keys) {
  if (keys.first == keys.second || track.interpolation == Interpolation::Step)
    return glm::vec3(track.values[valueIndex(track, keys.first)]);
  if (track.interpolation == Interpolation::CubicSpline) return glm::vec3(hermite(track, keys));
  glm::vec3 a(track.values[keys.first]), b(track.values[keys.second]);
  return a + (b - a) * keys.u;
}

glm::quat quatAt(const Track& track, const KeyPair& keys, QuatInterpolation method) {
  if (keys.first == keys.second || track.interpolation == Interpolation::Step)
    return safeNormalize(toQuat(track.values[valueIndex(track, keys.first)]));
  if (track.interpolation == Interpolation::CubicSpline) return hermiteQuat(track, keys);
  const glm::quat a = toQuat(track.values[keys.first]), b = toQuat(track.values[keys.second]);
  return method == QuatInterpolation::Nlerp ? nlerp(a, b, keys.u) : slerp(a, b, keys.u);
}

void weightsAt(const MorphTrack& track, const KeyPair& keys, std::span<float> out) {
  const std::size_t n = static_cast<std::size_t>(track.targets);
  // The block of key k's values: after its in-tangents for CubicSpline.
  auto values = [&](std::size_t key) {
    return track.values.data() + (track.interpolation == Interpolation::CubicSpline ? (key * 3 + 1) * n : key * n);
  };
  const float* v0 = values(keys.first);
  if (keys.first == keys.second || track.interpolation == Interpolation::Step) {
    std::copy(v0, v0 + n, out.begin());
    return;
  }
  const float* v1 = values(keys.second);
  if (track.interpolation == Interpolation::Linear) {
    for (std::size_t i = 0; i < n; ++i) out[i] = v0[i] + (v1[i] - v0[i]) * keys.u;
    return;
  }
  const HermiteBasis h(keys);
  const float* b0 = v0 + n;  // the first key's out-tangents follow its values
  const float* a1 = v1 - n;  // the second key's in-tangents precede its values
  for (std::size_t i = 0; i < n; ++i)
    out[i] = h.value0 * v0[i] + h.outTangent0 * b0[i] + h.value1 * v1[i] + h.inTangent1 * a1[i];
}

void applyAt(const Track& track, const KeyPair& keys, Srt& srt, QuatInterpolation method) {
  switch (track.path) {
    case AnimPath::Translation: srt.translation = vec3At(track, keys); break;
    case AnimPath::Rotation: srt.rotation = quatAt(track, keys, method); break;
    case AnimPath::Scale: srt.scale = vec3At(track, keys); break;
  }
}

}  // namespace

void Clip::groupTracks() {
  for (const Track& track : tracks_) jointsDriven_ = std::max(jointsDriven_, static_cast<std::size_t>(track.joint) + 1);
  for (std::size_t i = 0; i < tracks_.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (tracks_[i].joint == tracks_[j].joint && tracks_[i].path == tracks_[j].path) return;
  grouped_ = true;
  std::vector<std::vector<std::uint32_t>> linear(timelines_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (tracks_[i].interpolation == Interpolation::Linear) {
      linear[static_cast<std::size_t>(tracks_[i].timeline)].push_back(static_cast<std::uint32_t>(i));
    } else {
      others_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  for (std::size_t t = 0; t < timelines_.size(); ++t) blocks_.emplace_back(tracks_, linear[t], timelines_[t].size());
  std::vector<unsigned> parts(jointsDriven_, 0u);  // a bit per AnimPath
  for (const Track& t : tracks_) parts[static_cast<std::size_t>(t.joint)] |= 1u << static_cast<unsigned>(t.path);
  for (std::size_t j = 0; j < parts.size(); ++j)
    if (parts[j] != 7u) partlyDriven_.push_back(static_cast<std::uint32_t>(j));
}

int Clip::timelineOf(const std::vector<float>& times) {
  auto it = std::find(timelines_.begin(), timelines_.end(), times);
  if (it == timelines_.end()) it = timelines_.insert(it, times);
  return static_cast<int>(it - timelines_.begin());
}

void SamplingContext::bind(const Clip& clip) {
  if (clip_ == clip.id() && timelines_.size() == clip.timelines().size() &&
      morphTracks_.size() == clip.morphTracks().size())
    return;
  clip_ = clip.id();
  timelines_.assign(clip.timelines().size(), 0);
  keys_.resize(clip.timelines().size());
  morphTracks_.assign(clip.morphTracks().size(), 0);
}

void sampleTracks(const Clip& clip, double time, std::span<Srt> output, QuatInterpolation method,
                  SamplingContext& context) {
  context.bind(clip);
  const std::span<const std::vector<float>> timelines = clip.timelines();
  const std::span<KeyCursor> cursors = context.timelineCursors();
  const std::span<KeyPair> keys = context.timelineKeys();
  for (std::size_t t = 0; t < timelines.size(); ++t) keys[t] = findKeys(timelines[t], time, cursors[t]);
  const std::span<const Track> tracks = clip.tracks();
  if (!clip.grouped()) {
    for (const Track& track : tracks)
      applyAt(track, keys[static_cast<std::size_t>(track.timeline)], output[static_cast<std::size_t>(track.joint)], method);
    return;
  }
  const std::span<const KeyBlocks> blocks = clip.linearBlocks();
  for (std::size_t t = 0; t < blocks.size(); ++t) {
    if (keys[t].first != keys[t].second) {
      blocks[t].sample(keys[t], method, output);
      continue;
    }
    for (const std::uint32_t i : blocks[t].tracks())  // outside the keys: the end key held
      applyAt(tracks[i], keys[t], output[static_cast<std::size_t>(tracks[i].joint)], method);
  }
  for (const std::uint32_t i : clip.otherTracks())
    applyAt(tracks[i], keys[static_cast<std::size_t>(tracks[i].timeline)], output[static_cast<std::size_t>(tracks[i].joint)],
            method);
}

glm::vec3 sampleVec3(const Track& track, double time) { return vec3At(track, findKeys(track.times, time)); }

glm::quat sampleQuat(const Track& track, double time, QuatInterpolation method) {
  return quatAt(track, findKeys(track.times, time), method);
}

void sampleWeights(const MorphTrack& track, double time, std::span<float> out) {
  weightsAt(track, findKeys(track.times, time), out);
}
void sampleWeights(const MorphTrack& track, double time, std::span<float> out, KeyCursor& cursor) {
  weightsAt(track, findKeys(track.times, time, cursor), out);
}

void applyTrack(const Track& track, double time, Srt& srt, QuatInterpolation method) {
  applyAt(track, findKeys(track.times, time), srt, method);
}

}  // namespace engine
