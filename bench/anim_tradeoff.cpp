// anim_tradeoff: the animation shortcuts side by side, time and error.
//   slerp vs nlerp: rotation keys interpolated exactly or by normalised lerp; the
//     error is the largest vertex distance between the two skinned poses.
//   LBS vs DQS: linear-blend against dual-quaternion skinning of the same pose;
//     neither is ground truth, so the error column is their difference.
// Errors are relative to the model's bounding-box diagonal; times are medians over
// repeated passes on one core. Usage: anim_tradeoff [MODEL.gltf ...] [--out DIR]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "asset/gltf_loader.h"

using namespace engine;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kSamplesPerClip = 240;
constexpr int kRepeats = 7;

struct SkinnedPrim {
  const PrimitiveData* prim;
  const Skin* skin;
};

struct Model {
  std::string name;
  ModelData data;
  AnimatedModel animated;
  std::vector<SkinnedPrim> prims;
  size_t vertices = 0;
};

// A job that rejects its inputs is a bug in this program: stop, naming the step.
void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "anim_tradeoff: %s rejected its inputs\n", what);
  std::exit(1);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void pose(const Model& m, const Clip& clip, double t, QuatInterpolation q, std::vector<Srt>& locals,
          std::vector<glm::mat4>& models) {
  const Skeleton& s = m.animated.skeleton;
  SamplingJob job{&clip, t, s.restPose(), locals};
  job.rotations = q;
  require(job.run() && LocalToModelJob{s.parents(), locals, glm::mat4(1.0f), models}.run(), "posing");
}

// Skins every skinned primitive of the model; returns all positions, in order.
std::vector<glm::vec3> skinAll(const Model& m, const std::vector<glm::mat4>& models, SkinningMethod method) {
  std::vector<glm::vec3> out;
  for (const SkinnedPrim& sp : m.prims) {
    std::vector<glm::vec3> positions(sp.prim->positions.size());
    require(skinPrimitive(*sp.prim, *sp.skin, models, method, positions), "skinning");
    out.insert(out.end(), positions.begin(), positions.end());
  }
  return out;
}

double diagonal(const std::vector<glm::vec3>& p) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
  return glm::length(hi - lo);
}

double maxDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(glm::length(a[i] - b[i])));
  return worst;
}

struct Row {
  std::string model, family, setting;
  double time;  // ns per joint (sampling) or ns per vertex (skinning)
  std::string unit;
  double error;  // relative to the bbox diagonal
};

void measure(const Model& m, std::vector<Row>& rows) {
  const size_t joints = size_t(m.animated.skeleton.jointCount());
  std::vector<Srt> locals(joints);
  std::vector<glm::mat4> models(joints), modelsN(joints);
  double worstInterp = 0.0, worstSkin = 0.0;
  for (const Clip& clip : m.animated.clips) {
    for (int i = 0; i < kSamplesPerClip; ++i) {
      const double t = clip.duration() * (i + 0.37) / kSamplesPerClip;
      pose(m, clip, t, QuatInterpolation::Slerp, locals, models);
      pose(m, clip, t, QuatInterpolation::Nlerp, locals, modelsN);
      const auto lbs = skinAll(m, models, SkinningMethod::Linear);
      const double diag = diagonal(lbs);
      worstInterp = std::max(worstInterp, maxDistance(lbs, skinAll(m, modelsN, SkinningMethod::Linear)) / diag);
      worstSkin = std::max(worstSkin, maxDistance(lbs, skinAll(m, models, SkinningMethod::DualQuat)) / diag);
    }
  }
  const Clip& clip = m.animated.clips.front();
  for (QuatInterpolation q : {QuatInterpolation::Slerp, QuatInterpolation::Nlerp}) {
    std::vector<double> ns;
    for (int r = 0; r < kRepeats; ++r) {
      const auto start = Clock::now();
      for (int i = 0; i < kSamplesPerClip; ++i) {
        SamplingJob job{&clip, clip.duration() * i / kSamplesPerClip, m.animated.skeleton.restPose(), locals};
        job.rotations = q;
        require(job.run(), "sampling");
      }
      ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() / kSamplesPerClip / double(joints));
    }
    const bool slerp = q == QuatInterpolation::Slerp;
    rows.push_back({m.name, "interpolation", slerp ? "slerp" : "nlerp", median(ns), "ns/joint (sampling)",
                    slerp ? 0.0 : worstInterp});
  }
  pose(m, clip, 0.4, QuatInterpolation::Slerp, locals, models);
  for (SkinningMethod method : {SkinningMethod::Linear, SkinningMethod::DualQuat}) {
    std::vector<double> ns;
    for (int r = 0; r < kRepeats; ++r) {
      const auto start = Clock::now();
      for (int i = 0; i < 20; ++i) skinAll(m, models, method);
      ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() / 20.0 / double(m.vertices));
    }
    const bool lbs = method == SkinningMethod::Linear;
    rows.push_back({m.name, "skinning (CPU)", lbs ? "LBS" : "DQS", median(ns), "ns/vertex", lbs ? 0.0 : worstSkin});
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  std::string outDir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      outDir = argv[++i];
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "anim_tradeoff: unknown option %s\n", a.c_str());
      return 2;
    } else {
      paths.push_back(a);
    }
  }
  if (paths.empty()) {
    paths.push_back(std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf");
    const std::string cesium = std::string(ENGINE_SOURCE_DIR) + "/../shared/conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb";
    if (std::filesystem::exists(cesium)) paths.push_back(cesium);
  }
  std::vector<Row> rows;
  for (const auto& path : paths) {
    auto data = loadGltf(path);
    if (!data) return std::fprintf(stderr, "anim_tradeoff: %s\n", data.error().message.c_str()), 2;
    auto animated = buildAnimatedModel(*data);
    if (!animated) return std::fprintf(stderr, "anim_tradeoff: %s\n", animated.error().message.c_str()), 2;
    Model m{std::filesystem::path(path).stem().string(), std::move(data).value(), std::move(animated).value(), {}, 0};
    for (const NodeData& node : m.data.nodes) {
      if (node.mesh < 0 || node.skin < 0) continue;
      for (const PrimitiveData& p : m.data.meshes[size_t(node.mesh)].primitives) {
        if (p.influences == 0) continue;
        m.prims.push_back({&p, &m.animated.skins[size_t(node.skin)]});
        m.vertices += p.positions.size();
      }
    }
    if (m.prims.empty() || m.animated.clips.empty()) continue;
    measure(m, rows);
  }
  std::string table = "| model | family | setting | time | unit | largest vertex error / bbox diagonal |\n|---|---|---|---:|---|---:|\n";
  std::string csv = "model,family,setting,time,unit,max_relative_error\n";
  for (const Row& r : rows) {
    char line[256], error[32];
    std::snprintf(error, sizeof error, "%.2e", r.error);
    std::snprintf(line, sizeof line, "| %s | %s | %s | %.1f | %s | %s |\n", r.model.c_str(), r.family.c_str(),
                  r.setting.c_str(), r.time, r.unit.c_str(), r.error == 0.0 ? "reference" : error);
    table += line;
    std::snprintf(line, sizeof line, "%s,%s,%s,%.3f,%s,%.3g\n", r.model.c_str(), r.family.c_str(), r.setting.c_str(),
                  r.time, r.unit.c_str(), r.error);
    csv += line;
  }
  std::fputs(table.c_str(), stdout);
  if (!outDir.empty()) {
    std::filesystem::create_directories(outDir);
    std::ofstream(outDir + "/animation.md") << table;
    std::ofstream(outDir + "/animation.csv") << csv;
  }
  return 0;
}
