// anim_crowd: our side of the animation yardstick (bench/anim_vs_ozz runs it beside
// ../shared/anchors/perf/ozz_bench.cpp): sampling + local-to-model for N characters
// of one clip on one thread, each character with its own time (uniform in [0, D)),
// its own pose buffers and, unless --path reference, its own SamplingContext.
//   forward: every frame each character's time advances by 1/60 s, wrapping at D
//   random:  every frame each character samples a fresh random time (a precomputed
//            table), so the cursors are of no help and every track searches.
// Timing as the ozz harness does it: a frame = all N characters once; frames are timed
// in blocks of >= 200 us; a run = the median block / frames per block; the result is
// the median of --runs runs after one untimed warm-up run. Prints one
//   RESULT kind=anim label=L seek=forward|random chars=N ... chars_per_ms=C
// line per mode (plus sampling-only and local-to-model-only splits), and with --skin
// the CPU skinning (LBS, positions and normals, 4 influences) of every skinned
// primitive in ns per vertex.
// Usage: anim_crowd --model M.glb [--clip NAME|INDEX] [--label L] [--chars 1000]
//                   [--path cursor|reference] [--rotations slerp|nlerp]
//                   [--runs 5] [--blocks 30] [--skin] [--frames N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "asset/gltf_loader.h"

using namespace engine;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  std::string model, clip, label = "model", path = "cursor", rotations = "slerp";
  int chars = 1000, runs = 5, blocks = 30, frames = 0;
  bool skin = false;
};

struct Character {
  double time = 0.0;
  SamplingContext context;
  std::vector<Srt> locals;
  std::vector<glm::mat4> models;
};

struct Crowd {
  const AnimatedModel* animated = nullptr;
  const Clip* clip = nullptr;
  bool cursor = true;
  QuatInterpolation rotations = QuatInterpolation::Slerp;
  std::vector<Character> chars;
  std::vector<double> randomTimes;  // 65536 uniform times in [0, D)
  unsigned next = 0;
};

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "anim_crowd: %s\n", message.c_str());
  std::exit(2);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Median ns per frame of `frame` (see the header: blocks of >= 200 us, median of runs).
template <typename F>
double timeFrames(F&& frame, const Options& o) {
  using ns = std::chrono::duration<double, std::nano>;
  int perBlock = 1;
  for (;;) {
    const auto start = Clock::now();
    for (int i = 0; i < perBlock; ++i) frame();
    if (ns(Clock::now() - start).count() >= 200e3 || perBlock >= (1 << 22)) break;
    perBlock *= 2;
  }
  for (int b = 0; b < o.blocks; ++b)
    for (int i = 0; i < perBlock; ++i) frame();
  std::vector<double> runs;
  for (int r = 0; r < o.runs; ++r) {
    std::vector<double> blocks;
    for (int b = 0; b < o.blocks; ++b) {
      const auto start = Clock::now();
      for (int i = 0; i < perBlock; ++i) frame();
      blocks.push_back(ns(Clock::now() - start).count() / perBlock);
    }
    runs.push_back(median(blocks));
  }
  return median(runs);
}

double nextTime(Crowd& crowd, Character& c, bool random) {
  if (random) return crowd.randomTimes[crowd.next++ & 0xffff];
  c.time += 1.0 / 60.0;
  if (c.time >= crowd.clip->duration()) c.time -= crowd.clip->duration();
  return c.time;
}

void sample(const Crowd& crowd, Character& c, double time) {
  SamplingJob job{crowd.clip, time, crowd.animated->skeleton.restPose(), c.locals, crowd.rotations};
  if (crowd.cursor) job.context = &c.context;
  if (!job.run()) fail("SamplingJob rejected its inputs");
}

void toModel(const Crowd& crowd, Character& c) {
  if (!LocalToModelJob{crowd.animated->skeleton.parents(), c.locals, glm::mat4(1.0f), c.models,
                       crowd.animated->staticModels}
           .run())
    fail("LocalToModelJob rejected its inputs");
}

void makeCharacters(Crowd& crowd, int n) {
  const std::size_t joints = std::size_t(crowd.animated->skeleton.jointCount());
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> u(0.0, crowd.clip->duration());
  crowd.chars = std::vector<Character>(std::size_t(n));
  for (Character& c : crowd.chars) {
    c.time = u(rng);
    c.locals.resize(joints);
    c.models.resize(joints);
  }
}

void measureAnim(Crowd& crowd, const Options& o) {
  const int joints = crowd.animated->skeleton.jointCount();
  for (const bool random : {false, true}) {
    makeCharacters(crowd, o.chars);
    auto both = [&] {
      for (Character& c : crowd.chars) {
        sample(crowd, c, nextTime(crowd, c, random));
        toModel(crowd, c);
      }
    };
    auto sampling = [&] {
      for (Character& c : crowd.chars) sample(crowd, c, nextTime(crowd, c, random));
    };
    auto localToModel = [&] {
      for (Character& c : crowd.chars) toModel(crowd, c);
    };
    const double frame = timeFrames(both, o), s = timeFrames(sampling, o), l = timeFrames(localToModel, o);
    const double perChar = frame / o.chars;
    std::printf("RESULT kind=anim label=%s seek=%s chars=%d joints=%d path=%s rotations=%s frame_us=%.3f "
                "ns_per_char=%.1f ns_per_joint=%.2f chars_per_ms=%.0f sampling_ns_per_joint=%.2f "
                "ltm_ns_per_joint=%.2f\n",
                o.label.c_str(), random ? "random" : "forward", o.chars, joints, o.path.c_str(), o.rotations.c_str(),
                frame * 1e-3, perChar, perChar / joints, 1e6 / perChar, s / o.chars / joints, l / o.chars / joints);
    std::fflush(stdout);
  }
}

// --frames N: N forward frames, untimed, a fixed amount of work for `perf stat`
// (cycles in user mode vary less than time on a loaded machine).
void playFrames(Crowd& crowd, const Options& o) {
  makeCharacters(crowd, o.chars);
  for (int f = 0; f < o.frames; ++f)
    for (Character& c : crowd.chars) {
      sample(crowd, c, nextTime(crowd, c, false));
      toModel(crowd, c);
    }
}

// LBS of every skinned primitive (positions + normals), the pose of character 0.
void measureSkinning(const ModelData& data, const AnimatedModel& animated, Crowd& crowd, const Options& o) {
  makeCharacters(crowd, 1);
  Character& c = crowd.chars.front();
  sample(crowd, c, c.time);
  toModel(crowd, c);
  std::vector<std::pair<const PrimitiveData*, const Skin*>> prims;
  std::size_t vertices = 0;
  for (const NodeData& node : data.nodes) {
    if (node.mesh < 0 || node.skin < 0) continue;
    for (const PrimitiveData& p : data.meshes[std::size_t(node.mesh)].primitives)
      if (p.influences > 0) prims.emplace_back(&p, &animated.skins[std::size_t(node.skin)]), vertices += p.positions.size();
  }
  if (prims.empty()) return;
  std::vector<std::vector<glm::vec3>> positions, normals;
  for (const auto& [p, skin] : prims) {
    positions.emplace_back(p->positions.size());
    normals.emplace_back(p->normals.empty() ? 0 : p->positions.size());
  }
  const double frame = timeFrames(
      [&] {
        for (std::size_t i = 0; i < prims.size(); ++i)
          if (!skinPrimitive(*prims[i].first, *prims[i].second, c.models, SkinningMethod::Linear, positions[i],
                             normals[i]))
            fail("skinning rejected its inputs");
      },
      o);
  std::printf("RESULT kind=skin label=%s vertices=%zu attrs=pos+nrm ns_per_vertex=%.2f\n", o.label.c_str(), vertices,
              frame / double(vertices));
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--skin") {
      o.skin = true;
      continue;
    }
    if (i + 1 >= argc) fail("option " + k + " needs a value");
    const std::string v = argv[++i];
    if (k == "--model") o.model = v;
    else if (k == "--clip") o.clip = v;
    else if (k == "--label") o.label = v;
    else if (k == "--path") o.path = v;
    else if (k == "--rotations") o.rotations = v;
    else if (k == "--chars") o.chars = std::atoi(v.c_str());
    else if (k == "--runs") o.runs = std::atoi(v.c_str());
    else if (k == "--blocks") o.blocks = std::atoi(v.c_str());
    else if (k == "--frames") o.frames = std::atoi(v.c_str());
    else fail("unknown option " + k);
  }
  if (o.model.empty()) fail("usage: anim_crowd --model M.glb [--clip C] [--label L] [--chars N] [--path cursor|reference] "
                            "[--rotations slerp|nlerp] [--runs R] [--blocks B] [--skin] [--frames N]");
  if (o.path != "cursor" && o.path != "reference") fail("--path is cursor or reference, not " + o.path);
  if (o.rotations != "slerp" && o.rotations != "nlerp") fail("--rotations is slerp or nlerp, not " + o.rotations);
  if (o.chars < 1 || o.runs < 1 || o.blocks < 1) fail("--chars, --runs and --blocks must be at least 1");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  auto data = loadGltf(o.model);
  if (!data) fail(data.error().message);
  auto animated = buildAnimatedModel(*data);
  if (!animated) fail(animated.error().message);
  auto clip = findClip(*animated, o.clip, o.model);
  if (!clip) fail(clip.error().message);
  if (*clip < 0) fail(o.model + ": no clip to play");
  Crowd crowd;
  crowd.animated = &*animated;
  crowd.clip = &animated->clips[std::size_t(*clip)];
  crowd.cursor = o.path == "cursor";
  crowd.rotations = o.rotations == "nlerp" ? QuatInterpolation::Nlerp : QuatInterpolation::Slerp;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, crowd.clip->duration());
  crowd.randomTimes.resize(1 << 16);
  for (double& t : crowd.randomTimes) t = u(rng);
  std::printf("INFO label=%s joints=%d tracks=%zu duration_s=%.4f\n", o.label.c_str(), animated->skeleton.jointCount(),
              crowd.clip->tracks().size(), crowd.clip->duration());
  if (o.frames > 0) return playFrames(crowd, o), 0;
  measureAnim(crowd, o);
  if (o.skin) measureSkinning(*data, *animated, crowd, o);
  return 0;
}
