// The demo window's trade panel (issue #17's first part): every render knob of the
// scene file and the command line changed live over the same loaded scene, another
// scene picked from the scene's folder, time paused, slowed or scrubbed, and what
// the frame costs per pass on the GPU (GL_TIME_ELAPSED) with a history.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "asset/scene_file.h"
#include "scene_game.h"

namespace demo {
namespace {

// A knob: the choices it offers, and the override it sets (0 = the scene's own).
bool pickInt(const char* label, int& value, std::initializer_list<int> choices) {
  bool changed = false;
  const std::string current = std::to_string(value);
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (int choice : choices) {
      if (ImGui::Selectable(std::to_string(choice).c_str(), choice == value)) {
        changed = choice != value;
        value = choice;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool pickDouble(const char* label, double& value, std::initializer_list<double> choices) {
  bool changed = false;
  char current[32];
  std::snprintf(current, sizeof current, "%g", value);
  if (ImGui::BeginCombo(label, current)) {
    for (double choice : choices) {
      char name[32];
      std::snprintf(name, sizeof name, "%g", choice);
      if (ImGui::Selectable(name, choice == value)) {
        changed = choice != value;
        value = choice;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

const std::map<std::string, engine::SkinMode>& skinModeNames() {
  static const std::map<std::string, engine::SkinMode> names{
      {"lbs", engine::SkinMode::Linear}, {"dqs", engine::SkinMode::DualQuat}, {"none", engine::SkinMode::None}};
  return names;
}

const std::map<std::string, engine::QuatInterpolation>& rotationNames() {
  static const std::map<std::string, engine::QuatInterpolation> names{{"slerp", engine::QuatInterpolation::Slerp},
                                                                      {"nlerp", engine::QuatInterpolation::Nlerp}};
  return names;
}

// A knob over named choices (the scene file's names for them).
template <typename Enum>
bool pickNamed(const char* label, std::optional<Enum>& value, const std::map<std::string, Enum>& names) {
  bool changed = false;
  std::string current = value ? "?" : "(each model's)";
  for (const auto& [name, choice] : names)
    if (value == choice) current = name;
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (const auto& [name, choice] : names) {
      if (ImGui::Selectable(name.c_str(), value == choice) && value != choice) {
        value = choice;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

std::vector<std::string> sceneFiles(const std::string& scenePath) {
  std::vector<std::string> files;
  std::error_code ec;
  const auto folder = std::filesystem::path(scenePath).parent_path();
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// The effective value of each knob: the override, or the scene's own.
engine::SceneRenderOptions effective(const engine::SceneRenderOptions& o, const engine::SceneDesc& scene) {
  engine::SceneRenderOptions e = o;
  const engine::RenderDesc& r = scene.render;
  if (e.msaaOverride <= 0) e.msaaOverride = r.msaa;
  if (e.supersampleOverride <= 0) e.supersampleOverride = r.supersample;
  if (e.shadowMapOverride <= 0) e.shadowMapOverride = r.shadowMapSize;
  if (e.pcfKernelOverride <= 0) e.pcfKernelOverride = r.shadowFilter == engine::ShadowFilter::Hard ? 1 : r.pcfKernel;
  if (e.reflectionProbeOverride < 0) e.reflectionProbeOverride = r.reflectionProbe;
  if (e.iblSizeOverride <= 0) e.iblSizeOverride = r.iblSize;
  if (!e.ambientOverride) e.ambientOverride = engine::ambientOf(scene);
  if (!e.skinningOverride) e.skinningOverride = r.skinning;
  if (!e.lodPixelsOverride) e.lodPixelsOverride = r.lodPixels;
  if (e.terrainErrorOverride <= 0.0) e.terrainErrorOverride = scene.terrain.errorPixels;
  if (!e.shadingOverride) e.shadingOverride = r.shading;
  if (e.exposureOverride <= 0.0f) e.exposureOverride = r.exposure;
  if (!e.toneMapOverride) e.toneMapOverride = r.toneMap;
  if (!e.outputOverride) e.outputOverride = r.output;
  return e;
}

// With a planet's atmosphere and a sun: the sun's elevation, live (the sky's
// tables and the ambient's environment are rebuilt at the next frame).
void timeOfDay(engine::SceneRenderer& renderer) {
  if (!renderer.scene().atmosphere.enabled) return;
  float elevation = float(renderer.sunElevationDegrees());
  if (std::isnan(elevation)) return;
  if (ImGui::SliderFloat("sun elevation", &elevation, -10.0f, 90.0f, "%.1f deg")) renderer.setSunElevation(elevation);
}

void knobs(SceneGame& game) {
  const engine::SceneDesc& scene = game.renderer()->scene();
  engine::SceneRenderOptions o = effective(game.options(), scene);
  bool changed = pickInt("MSAA", o.msaaOverride, {1, 2, 4, 8});
  changed |= pickInt("supersample", o.supersampleOverride, {1, 2, 3});
  changed |= pickInt("shadow map", o.shadowMapOverride, {256, 512, 1024, 2048, 4096});
  changed |= pickInt("PCF kernel", o.pcfKernelOverride, {1, 3, 5, 7, 9});
  changed |= pickInt("probe size", o.reflectionProbeOverride, {0, 64, 128, 256, 512});
  changed |= pickNamed("shading", o.shadingOverride, engine::shadingNames());
  if (*o.shadingOverride == engine::Shading::Pbr) {
    changed |= pickNamed("ambient", o.ambientOverride, engine::ambientNames());
    changed |= pickInt("IBL size", o.iblSizeOverride, {16, 32, 64, 128, 256});
  }
  double exposure = o.exposureOverride;
  changed |= pickDouble("exposure", exposure, {0.25, 0.5, 1.0, 2.0, 4.0});
  o.exposureOverride = float(exposure);
  changed |= pickNamed("tone map", o.toneMapOverride, engine::toneMapNames());
  changed |= pickNamed("output", o.outputOverride, engine::outputNames());
  if (scene.terrain.enabled) changed |= pickDouble("LOD target (px)", o.terrainErrorOverride, {0.5, 1.0, 2.0, 4.0, 8.0});
  if (!scene.models.empty()) {
    changed |= pickNamed("skinning", o.skinningOverride, engine::skinningNames());
    changed |= pickNamed("skin blend", o.skinModeOverride, skinModeNames());
    changed |= pickDouble("model LOD (px)", *o.lodPixelsOverride, {0.0, 1.0, 2.0, 4.0, 8.0});
    std::optional<engine::QuatInterpolation> rotations = o.rotations;
    changed |= pickNamed("rotations", rotations, rotationNames());
    o.rotations = *rotations;
  }
  if (changed) (void)game.applyOptions(o);  // a failure shows in the panel
  timeOfDay(*game.renderer());
}

void timeControls(SceneGame& game) {
  TimeControl& t = game.timeControl();
  bool touched = ImGui::Checkbox("pause", &t.paused);
  float speed = float(t.speed);
  if (ImGui::SliderFloat("speed", &speed, -2.0f, 2.0f, "%.2fx")) {
    t.speed = speed;
    touched = true;
  }
  float now = float(t.time);
  if (ImGui::SliderFloat("time", &now, 0.0f, std::max(30.0f, now), "%.2f s")) {
    t.time = now;
    touched = true;
  }
  if (touched) t.taken = true;
}

void costs(SceneGame& game, GpuHistory& history) {
  const auto passes = game.renderer()->passTimes();
  double total = 0.0;
  for (const auto& p : passes) total += p.gpuMs;
  history.ms[size_t(history.next)] = float(total);
  history.next = (history.next + 1) % int(history.ms.size());
  ImGui::Text("GPU %.2f ms a frame", total);
  for (const auto& p : passes) {
    ImGui::ProgressBar(total > 0.0 ? float(p.gpuMs / total) : 0.0f, ImVec2(120, 0), "");
    ImGui::SameLine();
    ImGui::Text("%s %.2f ms", p.pass.c_str(), p.gpuMs);
  }
  ImGui::PlotLines("history", history.ms.data(), int(history.ms.size()), history.next, nullptr, 0.0f, FLT_MAX,
                   ImVec2(0, 50));
  const engine::SceneStats& s = game.renderer()->stats();
  ImGui::Text("%d draws, %d program changes (%d needed)", s.drawCalls, s.programChanges, s.programsNeeded);
  ImGui::Text("%d objects drawn, %d culled", s.objectsDrawn, s.objectsCulled);
  ImGui::Text("CPU: animation %.2f ms, culling %.2f ms, submission %.2f ms", s.animationMs, s.cullMs, s.submitMs);
}

void referenceControls(ReferencePanel& r) {
  int mode = int(r.mode);
  ImGui::RadioButton("off", &mode, int(ReferenceMode::Off));
  ImGui::SameLine();
  ImGui::RadioButton("split", &mode, int(ReferenceMode::Split));
  ImGui::SameLine();
  ImGui::RadioButton("reference", &mode, int(ReferenceMode::Reference));
  ImGui::SameLine();
  ImGui::RadioButton("heatmap", &mode, int(ReferenceMode::Heatmap));
  r.mode = ReferenceMode(mode);
  ImGui::Checkbox("path traced (else Whitted)", &r.pathTraced);
  pickInt("size divisor", r.divisor, {1, 2, 4, 8});
  if (r.mode == ReferenceMode::Off) return;
  if (!r.status.empty()) ImGui::TextWrapped("%s", r.status.c_str());
  if (r.view.running()) {
    ProgressiveTrace& t = *r.view.trace();
    ImGui::Text("%dx%d, pass %d of %d", t.width(), t.height(), t.passesDone(), t.passes());
  }
  if (r.error) {
    ImGui::Text("at %d spp: PSNR %.2f dB, mean error %.2f, SSIM %.4f", r.error->spp, r.error->psnr, r.error->meanAbs,
                r.error->ssim);
    if (r.error->noisePsnr) {
      ImGui::Text("the reference's own noise: %.1f dB%s", *r.error->noisePsnr,
                  r.error->psnr > *r.error->noisePsnr - 3.0 ? " (the raster is within it: trace longer)" : "");
    } else {
      ImGui::Text("the reference's own noise: needs 2 passes");
    }
  }
}

// Bookmarked views: go to one, drop one, or keep the view the camera has now.
void bookmarkControls(SceneGame& game, std::string& message) {
  const auto& views = game.bookmarks().all();
  int go = -1, drop = -1;
  for (int i = 0; i < int(views.size()); ++i) {
    ImGui::PushID(i);
    const glm::dvec3& p = views[size_t(i)].position;
    if (ImGui::Button("go")) go = i;
    ImGui::SameLine();
    if (ImGui::Button("x")) drop = i;
    ImGui::SameLine();
    ImGui::Text("%d: (%.1f, %.1f, %.1f)", i, p.x, p.y, p.z);
    ImGui::PopID();
  }
  if (go >= 0) game.goToBookmark(go);
  engine::Status s = engine::Ok{};
  if (drop >= 0) s = game.deleteBookmark(drop);
  if (ImGui::Button("bookmark this view")) s = game.bookmarkView();
  if (!s) message = s.error().message;
  if (!message.empty()) ImGui::TextWrapped("%s", message.c_str());
}

// "Add to table": the row goes where bench/tradeoff writes its own.
void addToTableButton(SceneGame& game, std::string& message) {
  if (ImGui::Button("add to table")) {
    const std::string csv = "out/tradeoff/results.csv";
    const engine::Status s = game.addToTable(csv);
    message = s ? "added to " + csv : s.error().message;
  }
  if (!message.empty()) ImGui::TextWrapped("%s", message.c_str());
}

}  // namespace

namespace {

engine::Result<int> knobInt(const std::string& name, const std::string& value, std::initializer_list<int> choices) {
  for (int c : choices)
    if (value == std::to_string(c)) return c;
  std::string list;
  for (int c : choices) list += (list.empty() ? "" : ", ") + std::to_string(c);
  return engine::makeError("--panel-set " + name + "=" + value + ": expected one of " + list);
}

template <typename Enum>
engine::Result<Enum> knobNamed(const std::string& name, const std::string& value, const std::map<std::string, Enum>& names) {
  if (auto it = names.find(value); it != names.end()) return it->second;
  std::string list;
  for (const auto& [n, e] : names) list += (list.empty() ? "" : ", ") + n;
  return engine::makeError("--panel-set " + name + "=" + value + ": expected one of " + list);
}

}  // namespace

// The same choices the combos offer (knobs above).
engine::Status SceneGame::parseKnob(const std::string& assignment, engine::SceneRenderOptions& o) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) return engine::makeError("--panel-set " + assignment + ": expected KNOB=VALUE");
  const std::string name = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  auto set = [](auto result, auto& field) -> engine::Status {
    if (!result) return result.error();
    field = *result;
    return engine::Ok{};
  };
  if (name == "msaa") return set(knobInt(name, value, {1, 2, 4, 8}), o.msaaOverride);
  if (name == "supersample") return set(knobInt(name, value, {1, 2, 3}), o.supersampleOverride);
  if (name == "shadow-map") return set(knobInt(name, value, {256, 512, 1024, 2048, 4096}), o.shadowMapOverride);
  if (name == "pcf") return set(knobInt(name, value, {1, 3, 5, 7, 9}), o.pcfKernelOverride);
  if (name == "probe") return set(knobInt(name, value, {0, 64, 128, 256, 512}), o.reflectionProbeOverride);
  if (name == "ibl-size") return set(knobInt(name, value, {16, 32, 64, 128, 256}), o.iblSizeOverride);
  if (name == "ambient") return set(knobNamed(name, value, engine::ambientNames()), o.ambientOverride);
  if (name == "skinning") return set(knobNamed(name, value, engine::skinningNames()), o.skinningOverride);
  if (name == "skin-blend") return set(knobNamed(name, value, skinModeNames()), o.skinModeOverride);
  if (name == "rotations") return set(knobNamed(name, value, rotationNames()), o.rotations);
  if (name == "shading") return set(knobNamed(name, value, engine::shadingNames()), o.shadingOverride);
  if (name == "tonemap") return set(knobNamed(name, value, engine::toneMapNames()), o.toneMapOverride);
  if (name == "output") return set(knobNamed(name, value, engine::outputNames()), o.outputOverride);
  if (name == "exposure") {
    for (double e : {0.25, 0.5, 1.0, 2.0, 4.0}) {
      char text[16];
      std::snprintf(text, sizeof text, "%g", e);
      if (value == text) {
        o.exposureOverride = float(e);
        return engine::Ok{};
      }
    }
    return engine::makeError("--panel-set exposure=" + value + ": expected one of 0.25, 0.5, 1, 2, 4");
  }
  if (name == "model-lod") {
    auto px = knobInt(name, value, {0, 1, 2, 4, 8});
    if (!px) return px.error();
    o.lodPixelsOverride = *px;
    return engine::Ok{};
  }
  if (name == "terrain-error") {
    auto px = knobInt(name, value, {1, 2, 4, 8});
    if (!px) return px.error();
    o.terrainErrorOverride = *px;
    return engine::Ok{};
  }
  return engine::makeError("--panel-set " + name + ": no such knob; knobs are msaa, supersample, shadow-map, pcf, "
                           "probe, shading, ambient, ibl-size, exposure, tonemap, output, skinning, skin-blend, rotations, model-lod, "
                           "terrain-error");
}

void SceneGame::drawUi() {
  if (!pendingKnobs_.empty()) {
    engine::SceneRenderOptions o = options_;
    for (const std::string& k : pendingKnobs_) (void)parseKnob(k, o);  // checked when queued
    pendingKnobs_.clear();
    (void)applyOptions(o);  // a failure shows in the panel
  }
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Trade");
  const std::string current = std::filesystem::path(desc_.path).filename().string();
  if (ImGui::BeginCombo("scene", current.c_str())) {
    for (const std::string& file : sceneFiles(desc_.path)) {
      const std::string name = std::filesystem::path(file).filename().string();
      if (ImGui::Selectable(name.c_str(), name == current) && name != current) (void)switchScene(file);
    }
    ImGui::EndCombo();
  }
  if (!lastError_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", lastError_.c_str());
  if (ImGui::CollapsingHeader("render", ImGuiTreeNodeFlags_DefaultOpen)) knobs(*this);
  if (ImGui::CollapsingHeader("time", ImGuiTreeNodeFlags_DefaultOpen)) timeControls(*this);
  if (ImGui::CollapsingHeader("camera")) bookmarkControls(*this, bookmarkMessage_);
  if (ImGui::CollapsingHeader("cost", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (showTimings_) {
      costs(*this, history_);
    } else {
      ImGui::TextWrapped("timings hidden (--panel-no-timings: a screenshot that is the same every run)");
    }
  }
  if (ImGui::CollapsingHeader("reference", ImGuiTreeNodeFlags_DefaultOpen)) {
    referenceControls(reference_);
    addToTableButton(*this, tableMessage_);
  }
  ImGui::End();
}

}  // namespace demo
