// Compares `viewer --dump-pose` (the program, as a user runs it) with the three.js
// reference poses of
// ../shared/conformance/poses (see CONVENTIONS.md there): node world matrices and
// skinned world-space vertex positions, for every pose whose model is present.
// The same for the morph target poses of tests/conformance/morph_poses (made by the
// same oracle, see the README there), which also compare each instance's weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anim/pose_dump.h"
#include "asset/gltf_loader.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path conformanceDir() {
  if (const char* env = std::getenv("CONFORMANCE_DIR")) return env;
  return fs::path(ENGINE_SOURCE_DIR) / ".." / "shared" / "conformance";
}

// Khronos's sample models (gltf-samples/) lie beside the conformance folder.
fs::path sharedDir() { return conformanceDir().parent_path(); }

fs::path morphPosesDir() { return fs::path(ENGINE_SOURCE_DIR) / "tests" / "conformance" / "morph_poses"; }

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// SimpleSkin and AnimatedTriangle store 3-decimal quaternion keys; three.js uses
// them unnormalised, the engine normalises, so CONVENTIONS.md says to compare
// those two against the *_nq.json files. A plain file with an _nq twin is
// therefore skipped in favour of the twin.
bool hasNormalisedTwin(const fs::path& pose) {
  std::string stem = pose.stem().string();
  if (endsWith(stem, "_nq")) return false;
  return fs::exists(pose.parent_path() / (stem + "_nq.json"));
}

struct PoseCase {
  fs::path file;
  std::string name;  // a valid GoogleTest name
  // Where the pose's "model" path may be relative to, tried in order.
  std::vector<fs::path> modelRoots;
};

// Names the file in test output instead of dumping the struct's bytes.
void PrintTo(const PoseCase& pose, std::ostream* os) { *os << pose.file.filename().string(); }

std::vector<PoseCase> findPoses(const fs::path& poses, const std::vector<fs::path>& modelRoots) {
  std::vector<PoseCase> cases;
  std::error_code ec;
  if (!fs::is_directory(poses, ec)) return cases;
  for (const auto& entry : fs::directory_iterator(poses, ec)) {
    if (entry.path().extension() != ".json" || hasNormalisedTwin(entry.path())) continue;
    std::string name = entry.path().stem().string();
    std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    cases.push_back({entry.path(), name, modelRoots});
  }
  std::sort(cases.begin(), cases.end(), [](const PoseCase& a, const PoseCase& b) { return a.name < b.name; });
  return cases;
}

std::vector<PoseCase> sharedPoses() { return findPoses(conformanceDir() / "poses", {conformanceDir()}); }
std::vector<PoseCase> morphPoses() { return findPoses(morphPosesDir(), {morphPosesDir(), sharedDir()}); }

fs::path modelOf(const PoseCase& pose, const std::string& model) {
  for (const fs::path& root : pose.modelRoots)
    if (fs::exists(root / model)) return root / model;
  return pose.modelRoots.back() / model;
}

json readJson(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

double bboxDiagonal(const json& ref) {
  const json& lo = ref["bbox"]["min"];
  const json& hi = ref["bbox"]["max"];
  double d2 = 0.0;
  for (int i = 0; i < 3; ++i) d2 += std::pow(hi[i].get<double>() - lo[i].get<double>(), 2);
  return std::sqrt(d2);
}

// Largest |world - reference| over the node matrices, relative to 1 + the largest
// reference entry so that translations far from the origin get a float's precision.
double nodeError(const json& ours, const json& ref) {
  std::map<int, const json*> byNode;
  for (const json& n : ours["nodes"]) byNode[n["node"].get<int>()] = &n["world"];
  double worst = 0.0;
  for (const json& n : ref["nodes"]) {
    auto it = byNode.find(n["node"].get<int>());
    if (it == byNode.end()) return INFINITY;
    double scale = 1.0;
    for (const json& v : n["world"]) scale = std::max(scale, std::abs(v.get<double>()));
    for (int i = 0; i < 16; ++i)
      worst = std::max(worst, std::abs((*it->second)[i].get<double>() - n["world"][i].get<double>()) / scale);
  }
  return worst;
}

// A pose's mesh instances by (node, mesh, primitive).
std::map<std::array<int, 3>, const json*> meshesByKey(const json& pose) {
  std::map<std::array<int, 3>, const json*> byKey;
  for (const json& m : pose["meshes"])
    byKey[{m["node"].get<int>(), m["mesh"].get<int>(), m["primitive"].get<int>()}] = &m;
  return byKey;
}

// Largest vertex distance over all mesh instances, or infinity when an instance
// or a vertex count does not match.
double positionError(const json& ours, const json& ref) {
  const auto byKey = meshesByKey(ours);
  double worst = 0.0;
  for (const json& m : ref["meshes"]) {
    auto it = byKey.find({m["node"].get<int>(), m["mesh"].get<int>(), m["primitive"].get<int>()});
    if (it == byKey.end()) return INFINITY;
    const json& a = (*it->second)["positions"];
    const json& b = m["positions"];
    if (a.size() != b.size()) return INFINITY;
    for (std::size_t v = 0; v + 2 < b.size(); v += 3) {
      double d2 = 0.0;
      for (std::size_t c = 0; c < 3; ++c) d2 += std::pow(a[v + c].get<double>() - b[v + c].get<double>(), 2);
      worst = std::max(worst, std::sqrt(d2));
    }
  }
  return worst;
}

// Largest |weight - reference| over the instances that have morph targets, or
// infinity when an instance or a weight count does not match. Zero without targets.
double morphWeightError(const json& ours, const json& ref) {
  const auto byKey = meshesByKey(ours);
  double worst = 0.0;
  for (const json& m : ref["meshes"]) {
    const json& b = m.value("morphWeights", json::array());
    if (b.empty()) continue;
    auto it = byKey.find({m["node"].get<int>(), m["mesh"].get<int>(), m["primitive"].get<int>()});
    if (it == byKey.end() || !it->second->contains("morphWeights")) return INFINITY;
    const json& a = (*it->second)["morphWeights"];
    if (a.size() != b.size()) return INFINITY;
    for (std::size_t i = 0; i < b.size(); ++i) worst = std::max(worst, std::abs(a[i].get<double>() - b[i].get<double>()));
  }
  return worst;
}

// Runs the viewer binary; the pose file it writes, or an empty object on failure.
json viewerPose(const fs::path& model, int anim, double time, engine::LoopMode loop) {
  const fs::path out = fs::temp_directory_path() / ("engine_pose_" + std::to_string(::getpid()) + ".json");
  char timeText[64];
  std::snprintf(timeText, sizeof timeText, "%.17g", time);
  const std::string command = std::string(ENGINE_BINARY_DIR) + "/bin/viewer '" + model.string() +
                              "' --anim " + std::to_string(anim) + " --time " + timeText + " --loop " +
                              (loop == engine::LoopMode::Clamp ? "clamp" : "repeat") + " --dump-pose '" +
                              out.string() + "' > /dev/null";
  const int rc = std::system(command.c_str());
  EXPECT_EQ(rc, 0) << command;
  if (rc != 0) return json::object();
  json pose = readJson(out);
  fs::remove(out);
  return pose;
}

class ConformanceTest : public ::testing::TestWithParam<PoseCase> {};

TEST_P(ConformanceTest, MatchesThreeJs) {
  const PoseCase& pose = GetParam();
  json ref = readJson(pose.file);
  fs::path modelPath = modelOf(pose, ref["model"].get<std::string>());
  if (!fs::exists(modelPath)) GTEST_SKIP() << "model not present: " << modelPath;
  int anim = ref["anim"].get<int>();
  double time = ref["time"].get<double>();
  engine::LoopMode loop = engine::LoopMode::Repeat;
  if (ref.contains("animation") && ref["animation"].is_object() &&
      ref["animation"].value("loop", "repeat") == "clamp")
    loop = engine::LoopMode::Clamp;
  const json ours = viewerPose(modelPath, anim, time, loop);
  ASSERT_TRUE(ours.contains("nodes")) << "viewer --dump-pose failed for " << pose.file;

  ASSERT_EQ(ours["nodes"].size(), ref["nodes"].size());
  double matrixErr = nodeError(ours, ref);
  double relErr = positionError(ours, ref) / bboxDiagonal(ref);
  // README: float32 engines land near 1e-6; 1e-4 of the bbox diagonal is the bar.
  // Node matrices are compared entry by entry, scaled by their largest entry.
  constexpr double limit = 1e-4;
  RecordProperty("position_error", std::to_string(relErr));
  std::printf("[ pose     ] %-45s position error %.3g of diagonal, matrix error %.3g\n", pose.file.stem().string().c_str(), relErr,
              matrixErr);
  EXPECT_LE(relErr, limit) << pose.file;
  EXPECT_LE(matrixErr, limit) << pose.file;
  // Weights are floats here and doubles in three.js, written to 9 digits.
  EXPECT_LE(morphWeightError(ours, ref), 1e-6) << pose.file;
}

INSTANTIATE_TEST_SUITE_P(Poses, ConformanceTest, ::testing::ValuesIn(sharedPoses()),
                         [](const ::testing::TestParamInfo<PoseCase>& p) { return p.param.name; });
INSTANTIATE_TEST_SUITE_P(MorphPoses, ConformanceTest, ::testing::ValuesIn(morphPoses()),
                         [](const ::testing::TestParamInfo<PoseCase>& p) { return p.param.name; });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ConformanceTest);

TEST(Conformance, FolderPresent) {
  if (!fs::is_directory(conformanceDir() / "poses"))
    GTEST_SKIP() << "no conformance material at " << conformanceDir()
                 << " (set CONFORMANCE_DIR); conformance poses not checked";
  EXPECT_FALSE(sharedPoses().empty());
}

// The repository's own poses are always there; only the Khronos models they
// name may be missing (then those cases skip).
TEST(Conformance, MorphPosesPresent) {
  const auto poses = morphPoses();
  EXPECT_GE(poses.size(), 20u) << morphPosesDir();
  for (const PoseCase& pose : poses) {
    const json ref = readJson(pose.file);
    const bool morphed = std::any_of(ref["meshes"].begin(), ref["meshes"].end(),
                                     [](const json& m) { return m.value("morphTargets", 0) > 0; });
    EXPECT_TRUE(morphed) << pose.file << " has no mesh with morph targets";
  }
}

}  // namespace
