// SamplingContext (key cursors per timeline) and the grouped, batched sampling it
// takes (Clip::linearBlocks: LINEAR keys in SoA blocks, four tracks at a time) against the
// search from scratch that SamplingJob and MorphSamplingJob do without one: every
// output bit must match, for any sequence of times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "asset/gltf_loader.h"

namespace engine {
namespace {

constexpr int kJoints = 36;  // one per track of the fixture, so that every track shows

Skeleton makeSkeleton() {
  RawSkeleton raw;
  for (int i = 0; i < kJoints; ++i) {
    raw.parents.push_back(i - 1);
    raw.restPose.push_back(Srt{glm::vec3(1.0f + 0.1f * float(i)), glm::quat(1, 0, 0, 0), glm::vec3(0, float(i), 0)});
  }
  return Skeleton::build(raw).value();
}

glm::vec4 randomQuat(std::mt19937& rng) {
  std::normal_distribution<float> n;
  return glm::vec4(n(rng), n(rng), n(rng), n(rng));  // Clip::build normalises LINEAR and STEP keys
}

// One track of `path` and `interpolation` on `times`, values random (rotations in
// random hemispheres; a run of equal keys to reach slerp's nlerp branch).
Track makeTrack(int joint, AnimPath path, Interpolation interpolation, const std::vector<float>& times,
                std::mt19937& rng) {
  Track t{joint, path, interpolation, times, {}};
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  const std::size_t perKey = interpolation == Interpolation::CubicSpline ? 3 : 1;
  for (std::size_t k = 0; k < times.size() * perKey; ++k) {
    const bool repeat = k >= 2 && k < 4 && perKey == 1;
    t.values.push_back(repeat ? t.values.back()
                              : path == AnimPath::Rotation ? randomQuat(rng) : glm::vec4(u(rng), u(rng), u(rng), 0.0f));
  }
  return t;
}

// Every path with every interpolation, on timelines shared by several tracks and
// timelines of their own: keys from 0, keys far from zero, repeated key times, one
// key. Morph tracks with each interpolation.
struct Fixture {
  Skeleton skeleton = makeSkeleton();
  MorphLayout morphs;  // nodes 2 (4 targets) and 5 (3 targets)
  Clip clip;

  // `shareJoints`: tracks drive joints 0-5 over and over, so that several drive one
  // joint's part and the last must win (glTF forbids it; the clip is not grouped).
  // `fullJoints`: each joint gets a translation, a rotation and a scale (the three
  // tracks of one timeline and interpolation), so that no part keeps its rest value.
  explicit Fixture(unsigned seed = 11, bool shareJoints = false, bool fullJoints = false) {
    morphs.first.assign(kJoints, -1);
    morphs.targets.assign(kJoints, 0);
    morphs.first[2] = 0, morphs.targets[2] = 4, morphs.first[5] = 4, morphs.targets[5] = 3;
    morphs.restWeights = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f};
    std::mt19937 rng(seed);
    const std::vector<std::vector<float>> timelines = {
        {0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 1.5f, 2.0f, 2.25f, 3.0f},
        {1000.0f, 1000.5f, 1001.0f, 1001.0f, 1002.5f},
        {0.5f},
        {0.1f, 0.1f, 0.7f, 1.9f, 2.9f, 3.1f},
    };
    RawClip raw{"mixed", {}, {}};
    int joint = 0;
    for (const auto& times : timelines)
      for (Interpolation in : {Interpolation::Step, Interpolation::Linear, Interpolation::CubicSpline})
        for (AnimPath path : {AnimPath::Translation, AnimPath::Rotation, AnimPath::Scale})
          raw.tracks.push_back(
              makeTrack(shareJoints ? joint++ % 6 : fullJoints ? joint++ / 3 : joint++, path, in, times, rng));
    std::uniform_real_distribution<float> w(0.0f, 1.0f);
    for (Interpolation in : {Interpolation::Step, Interpolation::Linear, Interpolation::CubicSpline}) {
      const std::size_t node = in == Interpolation::Linear ? 5 : 2, targets = node == 5 ? 3 : 4;
      MorphTrack m{int(node), -1, int(targets), in, timelines[in == Interpolation::CubicSpline ? 3 : 0], {}};
      m.values.resize(m.times.size() * targets * (in == Interpolation::CubicSpline ? 3 : 1));
      for (float& v : m.values) v = w(rng);
      raw.morphTracks.push_back(std::move(m));
    }
    clip = Clip::build(raw, skeleton, morphs).value();
  }
};

// memcmp of empty spans would pass it null pointers (undefined behaviour).
template <typename T>
bool sameBits(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}
bool sameBits(std::span<const Srt> a, std::span<const Srt> b) { return sameBits<Srt>(a, b); }
bool sameBits(std::span<const float> a, std::span<const float> b) { return sameBits<float>(a, b); }

// Samples `times` in order through one context and from scratch; stops at the
// first difference, reporting its time.
void expectSameAsSearch(const Clip& clip, const Skeleton& skeleton, const MorphLayout& morphs,
                        const std::vector<double>& times, QuatInterpolation rotations) {
  const std::size_t joints = std::size_t(skeleton.jointCount());
  std::vector<Srt> cursor(joints), search(joints);
  std::vector<float> cursorWeights(morphs.size()), searchWeights(morphs.size());
  SamplingContext context;
  for (double t : times) {
    // Whatever the output held before (here NaNs): every value is written.
    std::memset(static_cast<void*>(cursor.data()), 0xFF, cursor.size() * sizeof(Srt));
    ASSERT_TRUE((SamplingJob{&clip, t, skeleton.restPose(), cursor, rotations, &context}.run()));
    ASSERT_TRUE((SamplingJob{&clip, t, skeleton.restPose(), search, rotations}.run()));
    ASSERT_TRUE(sameBits(cursor, search)) << "pose differs at time " << t;
    ASSERT_TRUE((MorphSamplingJob{&clip, t, morphs.restWeights, cursorWeights, &context}.run()));
    ASSERT_TRUE((MorphSamplingJob{&clip, t, morphs.restWeights, searchWeights}.run()));
    ASSERT_TRUE(sameBits(cursorWeights, searchWeights)) << "morph weights differ at time " << t;
  }
}

// Sequences of every kind: forward at 1/60 s and at random strides, backward,
// random times, times exactly on keys, times far before and after the keys.
std::vector<std::vector<double>> timeSequences(const Clip& clip, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> any(-1.0, 1004.0), near(-0.5, 3.5), stride(0.0, 0.4);
  std::vector<double> keys;
  for (const auto& timeline : clip.timelines()) keys.insert(keys.end(), timeline.begin(), timeline.end());
  std::uniform_int_distribution<std::size_t> key(0, keys.size() - 1);
  std::vector<std::vector<double>> out(6);
  for (int i = 0; i < 400; ++i) {
    out[0].push_back(-0.2 + i / 60.0);
    out[1].push_back(3.4 - i / 60.0);
    out[2].push_back(i % 2 ? any(rng) : near(rng));
    out[3].push_back(keys[key(rng)]);
    out[4].push_back((out[4].empty() ? 998.0 : out[4].back()) + stride(rng));
    out[5].push_back(i % 7 == 0 ? near(rng) : (out[5].empty() ? 0.0 : out[5].back()) + 1.0 / 60.0);
  }
  return out;
}

TEST(SamplingContext, MatchesTheSearchBitForBitOnEveryInterpolation) {
  const Fixture f;
  ASSERT_EQ(f.clip.timelines().size(), 4u);  // shared timelines: 9 tracks on each
  ASSERT_TRUE(f.clip.grouped());
  for (unsigned seed = 1; seed <= 5; ++seed)
    for (const auto& times : timeSequences(f.clip, seed))
      for (QuatInterpolation q : {QuatInterpolation::Slerp, QuatInterpolation::Nlerp}) {
        expectSameAsSearch(f.clip, f.skeleton, f.morphs, times, q);
        if (HasFatalFailure()) return;
      }
}

// Joints driven in every part: the sampler writes them without their rest pose
// first (Clip::partlyDrivenJoints), and must write all of each.
TEST(SamplingContext, MatchesTheSearchWhenEveryPartIsDriven) {
  const Fixture f(5, false, true);
  ASSERT_TRUE(f.clip.grouped());
  ASSERT_LT(f.clip.partlyDrivenJoints().size(), f.clip.jointsDriven());
  for (const auto& times : timeSequences(f.clip, 4))
    for (QuatInterpolation q : {QuatInterpolation::Slerp, QuatInterpolation::Nlerp}) {
      expectSameAsSearch(f.clip, f.skeleton, f.morphs, times, q);
      if (HasFatalFailure()) return;
    }
}

TEST(SamplingContext, MatchesTheSearchWhenTracksShareATarget) {
  const Fixture f(7, true);
  ASSERT_FALSE(f.clip.grouped());
  for (const auto& times : timeSequences(f.clip, 9)) {
    expectSameAsSearch(f.clip, f.skeleton, f.morphs, times, QuatInterpolation::Slerp);
    if (HasFatalFailure()) return;
  }
}

// One context handed clips in turn at the same time follows each (both clips'
// cursors sit at the same key indices).
TEST(SamplingContext, FollowsAChangeOfClip) {
  const Fixture a(1), b(2);  // same layout, different keys
  const std::vector<double> times = {0.3, 0.31, 1.2};
  std::vector<Srt> cursor(kJoints), search(kJoints);
  SamplingContext context;
  for (double t : times)
    for (const Clip* clip : {&a.clip, &b.clip, &a.clip}) {
      ASSERT_TRUE((SamplingJob{clip, t, a.skeleton.restPose(), cursor, QuatInterpolation::Slerp, &context}.run()));
      ASSERT_TRUE((SamplingJob{clip, t, a.skeleton.restPose(), search}.run()));
      EXPECT_TRUE(sameBits(cursor, search)) << "time " << t;
    }
}

// A real glTF character (the shipped robot), every clip played forward at 60 Hz
// from a random start, then seeking at random.
TEST(SamplingContext, MatchesTheSearchOnTheShippedCharacter) {
  auto data = loadGltf(std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf");
  ASSERT_TRUE(data) << data.error().message;
  auto animated = buildAnimatedModel(*data);
  ASSERT_TRUE(animated);
  std::mt19937 rng(3);
  for (const Clip& clip : animated->clips) {
    std::uniform_real_distribution<double> u(0.0, clip.duration());
    std::vector<double> times;
    double t = u(rng);
    for (int i = 0; i < 300; ++i) times.push_back(i < 200 ? std::fmod(t += 1.0 / 60.0, clip.duration()) : u(rng));
    expectSameAsSearch(clip, animated->skeleton, animated->morphs, times, QuatInterpolation::Slerp);
  }
}

// The static ancestors a model's joints are built on (AnimatedModel::staticModels)
// give the bits of computing them, at every time of every clip: CesiumMan's Z_UP,
// Armature and mesh node, and the shipped robot's.
TEST(StaticModels, PoseAsTheWholeSkeletonDoes) {
  const std::string cesium = std::string(ENGINE_SOURCE_DIR) + "/../shared/conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb";
  for (const std::string& path : {cesium, std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf"}) {
    auto data = loadGltf(path);
    ASSERT_TRUE(data) << data.error().message;
    auto animated = buildAnimatedModel(*data);
    ASSERT_TRUE(animated);
    if (path == cesium) {
      ASSERT_EQ(animated->staticModels.size(), 3u);
      EXPECT_EQ(animated->skeleton.name(0), "Z_UP");
      EXPECT_EQ(animated->skeleton.name(1), "Armature");
      EXPECT_EQ(animated->skeleton.name(2), "Cesium_Man");  // the mesh's node, before the joints
    }
    const Skeleton& skeleton = animated->skeleton;
    std::vector<Srt> locals(skeleton.restPose().size());
    std::vector<glm::mat4> fixed(locals.size()), full(locals.size());
    std::mt19937 rng(4);
    for (const Clip& clip : animated->clips) {
      std::uniform_real_distribution<double> u(0.0, clip.duration());
      for (int i = 0; i < 200; ++i) {
        ASSERT_TRUE((SamplingJob{&clip, u(rng), skeleton.restPose(), locals}.run()));
        ASSERT_TRUE((LocalToModelJob{skeleton.parents(), locals, glm::mat4(1.0f), fixed, animated->staticModels}.run()));
        ASSERT_TRUE((LocalToModelJob{skeleton.parents(), locals, glm::mat4(1.0f), full}.run()));
        ASSERT_EQ(std::memcmp(fixed.data(), full.data(), full.size() * sizeof(glm::mat4)), 0) << path;
      }
    }
  }
}

}  // namespace
}  // namespace engine
