// Scene-file JSON -> engine::parseScene (loadSceneFile's parser, in memory). Any
// input gives a SceneDesc or an error naming the file; never a crash or a report.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "asset/scene_file.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::quietLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto scene = engine::parseScene(text, "fuzz.json");
  if (!scene && scene.error().message.rfind("fuzz.json", 0) != 0) std::abort();
  return 0;
}
