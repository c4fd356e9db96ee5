// Animation cost per frame: sampling + local-to-model + palette for a 50-joint
// character, CPU skinning throughput (LBS vs DQS), CPU morph targets, and slerp
// vs nlerp.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "anim/jobs.h"
#include "anim/skeleton.h"

namespace {

constexpr int kJoints = 50;
constexpr int kKeys = 31;  // 1 s at 30 Hz

// A spine of 10 joints with four 10-joint limbs hanging off it.
engine::Skeleton makeCharacter() {
  engine::RawSkeleton raw;
  for (int i = 0; i < kJoints; ++i) {
    int parent = i == 0 ? -1 : (i < 10 ? i - 1 : (i % 10 == 0 ? 9 - (i / 10) : i - 1));
    raw.parents.push_back(parent);
    raw.restPose.push_back(engine::Srt{glm::vec3(1), glm::quat(1, 0, 0, 0), glm::vec3(0, 0.2f, 0)});
  }
  return engine::Skeleton::build(raw).value();
}

// Translation, rotation and scale tracks on every joint, LINEAR.
engine::Clip makeClip(const engine::Skeleton& skeleton) {
  engine::RawClip raw;
  for (int j = 0; j < kJoints; ++j) {
    for (engine::AnimPath path : {engine::AnimPath::Translation, engine::AnimPath::Rotation, engine::AnimPath::Scale}) {
      engine::Track t{j, path, engine::Interpolation::Linear, {}, {}};
      for (int k = 0; k < kKeys; ++k) {
        float time = k / 30.0f;
        t.times.push_back(time);
        if (path == engine::AnimPath::Rotation) {
          glm::quat q = glm::angleAxis(std::sin(time * 6.0f + j) * 0.5f, glm::normalize(glm::vec3(1, j % 3, 1)));
          t.values.emplace_back(q.x, q.y, q.z, q.w);
        } else if (path == engine::AnimPath::Translation) {
          t.values.emplace_back(0.0f, 0.2f + 0.01f * std::sin(time * 4.0f), 0.0f, 0.0f);
        } else {
          t.values.emplace_back(1.0f, 1.0f + 0.05f * std::sin(time * 3.0f), 1.0f, 0.0f);
        }
      }
      raw.tracks.push_back(std::move(t));
    }
  }
  return engine::Clip::build(raw, skeleton).value();
}

void BM_CharacterPose(benchmark::State& state) {
  engine::Skeleton skeleton = makeCharacter();
  engine::Clip clip = makeClip(skeleton);
  std::vector<engine::Srt> locals(kJoints);
  std::vector<glm::mat4> models(kJoints), palette(kJoints), inverseBinds(kJoints, glm::mat4(1.0f));
  std::vector<int> joints(kJoints);
  for (int j = 0; j < kJoints; ++j) joints[static_cast<std::size_t>(j)] = j;
  engine::SamplingContext context;  // the player's way: key cursors kept between frames
  double t = 0.0;
  auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    t = std::fmod(t + 1.0 / 60.0, clip.duration());
    if (!engine::SamplingJob{&clip, t, skeleton.restPose(), locals, engine::QuatInterpolation::Slerp, &context}.run() ||
        !engine::LocalToModelJob{skeleton.parents(), locals, glm::mat4(1.0f), models}.run() ||
        !engine::SkinningPaletteJob{models, joints, inverseBinds, palette}.run()) {
      state.SkipWithError("a job rejected its inputs");
      break;
    }
    benchmark::DoNotOptimize(palette.data());
    benchmark::ClobberMemory();
  }
  // Wall time measured here so the counters read in plain units (Google
  // Benchmark's rate counters always print "/s").
  double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  double characters = static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations() * kJoints);
  state.counters["ns_per_joint"] = ns / (characters * kJoints);
  state.counters["characters_per_ms"] = characters / (ns * 1e-6);
}
BENCHMARK(BM_CharacterPose);

void BM_Skinning(benchmark::State& state) {
  const std::size_t vertices = 10000;
  auto method = static_cast<engine::SkinningMethod>(state.range(0));
  std::vector<glm::mat4> palette;
  for (int j = 0; j < kJoints; ++j)
    palette.push_back(engine::toMatrix(
        engine::Srt{glm::vec3(1), glm::angleAxis(j * 0.05f, glm::vec3(0, 1, 0)), glm::vec3(0, j * 0.1f, 0)}));
  std::vector<engine::DualQuat> dqs(palette.size());
  if (!engine::DualQuatPaletteJob{palette, dqs}.run()) {
    state.SkipWithError("DualQuatPaletteJob rejected its inputs");
    return;
  }
  std::vector<glm::vec3> positions(vertices), normals(vertices, glm::vec3(0, 0, 1)), outP(vertices), outN(vertices);
  std::vector<std::uint16_t> joints(vertices * 4);
  std::vector<float> weights(vertices * 4);
  for (std::size_t v = 0; v < vertices; ++v) {
    positions[v] = glm::vec3(std::sin(v * 0.1f), v * 0.001f, std::cos(v * 0.1f));
    for (std::size_t k = 0; k < 4; ++k) {
      joints[v * 4 + k] = static_cast<std::uint16_t>((v / 200 + k) % kJoints);
      weights[v * 4 + k] = k == 0 ? 0.55f : 0.15f;
    }
  }
  engine::SkinningJob job;
  job.method = method;
  job.positions = positions;
  job.normals = normals;
  job.joints = joints;
  job.weights = weights;
  job.palette = palette;
  job.dualQuats = dqs;
  job.outPositions = outP;
  job.outNormals = outN;
  for (auto _ : state) {
    if (!job.run()) {
      state.SkipWithError("SkinningJob rejected its inputs");
      break;
    }
    benchmark::DoNotOptimize(outP.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(vertices));
  state.SetLabel(method == engine::SkinningMethod::Linear ? "LBS, vertices/s" : "DQS, vertices/s");
}
BENCHMARK(BM_Skinning)->Arg(static_cast<int>(engine::SkinningMethod::Linear))
    ->Arg(static_cast<int>(engine::SkinningMethod::DualQuat));

// CPU morph targets (MorphJob) on 10k vertices, positions and normals, with
// range(0) targets all of non-zero weight: the cost grows with targets x vertices.
void BM_Morph(benchmark::State& state) {
  const std::size_t vertices = 10000, targets = static_cast<std::size_t>(state.range(0));
  std::vector<glm::vec3> positions(vertices), normals(vertices, glm::vec3(0, 0, 1)), outP(vertices), outN(vertices);
  std::vector<glm::vec3> deltas(vertices * targets);
  for (std::size_t i = 0; i < deltas.size(); ++i) deltas[i] = 0.01f * glm::vec3(std::sin(i * 0.3f), std::cos(i * 0.7f), 0.0f);
  std::vector<float> weights(targets);
  for (std::size_t t = 0; t < targets; ++t) weights[t] = 0.1f + 0.8f * std::sin(t * 1.3f) * std::sin(t * 1.3f);
  const engine::MorphJob job{weights, positions, deltas, outP, normals, deltas, outN, {}, {}, {}};
  for (auto _ : state) {
    if (!job.run()) {
      state.SkipWithError("MorphJob rejected its inputs");
      break;
    }
    benchmark::DoNotOptimize(outP.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(vertices * targets));
  state.SetLabel("vertex-targets/s");
}
BENCHMARK(BM_Morph)->Arg(1)->Arg(8)->Arg(64);

std::vector<glm::quat> randomQuats(std::size_t n, float seed) {
  std::vector<glm::quat> out;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back(glm::angleAxis(std::sin(i * 1.7f + seed) * 3.0f,
                                 glm::normalize(glm::vec3(std::sin(i + seed), 1.0f, std::cos(i * 0.3f)))));
  return out;
}

template <bool kSlerp>
void BM_QuatInterpolation(benchmark::State& state) {
  const std::size_t n = 1024;
  auto a = randomQuats(n, 0.0f), b = randomQuats(n, 1.0f);
  std::vector<glm::quat> out(n);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i)
      out[i] = kSlerp ? engine::slerp(a[i], b[i], 0.3f) : engine::nlerp(a[i], b[i], 0.3f);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(n));
}
BENCHMARK(BM_QuatInterpolation<true>)->Name("BM_Slerp");
BENCHMARK(BM_QuatInterpolation<false>)->Name("BM_Nlerp");

}  // namespace
