// glTF bytes -> ModelData -> buildAnimatedModel -> every clip sampled at times
// inside, at and outside its keys, through the same jobs the viewer runs
// (SamplingJob, LocalToModelJob) and the pose dump (which also skins on the CPU).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::quietLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto model = engine::loadGltfFromMemory(std::span(data, size), "fuzz.gltf");
  if (!model) return 0;
  auto built = engine::buildAnimatedModel(*model);
  if (!built) return 0;
  const engine::Skeleton& skeleton = built->skeleton;
  const std::size_t count = static_cast<std::size_t>(skeleton.jointCount());
  std::vector<engine::Srt> locals(count);
  std::vector<glm::mat4> models(count);
  for (const engine::Clip& clip : built->clips) {
    const double d = clip.duration();
    for (double t : {-1.0, 0.0, d * 0.37, d * 0.5, d, d + 1.0, 1e30}) {
      engine::SamplingJob sample{&clip, t, skeleton.restPose(), locals};
      if (!sample.run()) std::abort();  // a built clip must always sample
      engine::LocalToModelJob toModel{skeleton.parents(), locals, glm::mat4(1.0f), models};
      if (!toModel.run()) std::abort();
    }
  }
  // Pose dumps: the rest pose and each clip (bounded, big models are slow to dump).
  const int clips = static_cast<int>(std::min<std::size_t>(built->clips.size(), 4));
  for (int a = -1; a < clips; ++a)
    for (auto loop : {engine::LoopMode::Repeat, engine::LoopMode::PingPong}) {
      auto pose = engine::dumpPose(*model, a, 0.75, loop);
      if (!pose) std::abort();  // the model built, so its pose must dump
    }
  return 0;
}
