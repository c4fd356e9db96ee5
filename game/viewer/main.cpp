// viewer: plays the animations of any glTF 2.0 file. In a window with an ImGui
// panel (clips, play/pause, scrub, speed, loop, skeleton, bind pose, LBS/DQS);
// offscreen to a PNG; or, with --dump-pose, writes the pose at --time as JSON in
// the format of the conformance reference poses.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "anim/pose_dump.h"
#include "app/cli.h"
#include "asset/gltf_loader.h"
#include "asset/material_variants.h"
#include "core/float_image_io.h"
#include "viewer_scene.h"

namespace {

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "viewer: %s\n", message.c_str());
  return code;
}

engine::Status writeJson(const std::string& path, const nlohmann::json& json) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << json.dump() << "\n";
    if (!out) return engine::makeError(path + ": cannot write the pose");
  }
  std::filesystem::rename(tmp, path);
  return engine::Ok{};
}

// Whether the viewer can look through the file's camera `index`.
engine::Status checkCamera(const engine::ModelData& model, int index) {
  if (index >= int(model.cameras.size()))
    return engine::makeError("camera " + std::to_string(index) + " does not exist (the file has " +
                             std::to_string(model.cameras.size()) + ")");
  if (!model.cameras[size_t(index)].perspective)
    return engine::makeError("camera " + std::to_string(index) + " is orthographic; only perspective cameras are drawn");
  if (engine::cameraNode(model, index) < 0)
    return engine::makeError("camera " + std::to_string(index) + " is placed by no node");
  return engine::Ok{};
}

// Why --variant named nothing, with what the file has.
std::string variantList(const engine::ModelData& model, const std::string& asked) {
  if (model.variants.empty()) return "the file has no KHR_materials_variants";
  std::string names;
  for (const std::string& v : model.variants) names += (names.empty() ? "" : ", ") + v;
  return "no variant \"" + asked + "\" (the file has " + names + ")";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Animation playback viewer for glTF 2.0 files.", "viewer"};
  engine::CommonOptions options;
  std::string modelPath, anim, loop = "repeat", dumpPosePath, variant;
  int camera = -1;
  int sceneIndex = -1;
  std::string debugView = "none";
  double speed = 1.0;
  bool dualQuat = false, skeleton = false;
  app.add_option("model", modelPath, "glTF file (.gltf or .glb)")->required();
  app.add_option("--anim", anim, "Animation index or name (-1: rest pose; default: the first)");
  app.add_option("--speed", speed, "Playback speed (negative plays backwards)")->capture_default_str();
  app.add_option("--loop", loop, "Loop mode")->check(CLI::IsMember({"repeat", "clamp", "pingpong"}))
      ->capture_default_str();
  app.add_flag("--dq", dualQuat, "Dual-quaternion skinning instead of linear blend");
  app.add_flag("--skeleton", skeleton, "Draw the skeleton over the model");
  app.add_option("--variant", variant, "KHR_materials_variants: the variant to draw, by name or index (default: the file's materials)");
  app.add_option("--camera", camera, "Look through the file's camera INDEX, where its node stands (default: framed to the model)");
  app.add_option("--scene", sceneIndex, "The file's glTF scene INDEX to draw (default: its default scene)");
  app.add_option("--debug-view", debugView, "Draw one input as it is: " + engine::debugViewList());
  app.add_option("--dump-pose", dumpPosePath, "Write the pose at --time as JSON and exit");
  engine::addCommonOptions(app, options);
  if (auto code = engine::parseCommandLine(app, argc, argv)) return *code;
  if (!std::isfinite(speed)) return fail(engine::kExitBadInput, "--speed: must be finite");

  if (!dumpPosePath.empty()) {
    if (auto s = engine::checkWritable(dumpPosePath, "--dump-pose"); !s) {
      return fail(engine::kExitBadInput, s.error().message);
    }
  }
  if (sceneIndex < -1) return fail(engine::kExitBadInput, "--scene: must be a scene index (0 or more)");
  const auto view = engine::parseDebugView(debugView);
  if (!view) {
    return fail(engine::kExitBadInput, "--debug-view: no view \"" + debugView + "\"; views are: " + engine::debugViewList());
  }
  auto model = engine::loadGltf(modelPath, sceneIndex);
  if (!model) return fail(engine::kExitBadInput, model.error().message);
  auto animated = engine::buildAnimatedModel(*model);
  if (!animated) return fail(engine::kExitBadInput, animated.error().message);
  auto clip = engine::findClip(*animated, anim, modelPath);
  if (!clip) return fail(engine::kExitBadInput, modelPath + ": --anim: " + clip.error().message);
  int variantIndex = -1;
  if (!variant.empty()) {
    const auto found = engine::findVariant(*model, variant);
    if (!found) return fail(engine::kExitBadInput, modelPath + ": --variant: " + variantList(*model, variant));
    variantIndex = *found;
  }
  if (camera >= 0) {
    if (auto s = checkCamera(*model, camera); !s) return fail(engine::kExitBadInput, modelPath + ": --camera: " + s.error().message);
  }
  const engine::LoopMode loopMode = loop == "clamp"      ? engine::LoopMode::Clamp
                                    : loop == "pingpong" ? engine::LoopMode::PingPong
                                                         : engine::LoopMode::Repeat;
  if (!dumpPosePath.empty()) {
    auto pose = engine::dumpPose(*model, *clip, options.run.time.value_or(0.0) * speed, loopMode);
    if (!pose) return fail(engine::kExitBadInput, pose.error().message);
    if (auto s = writeJson(dumpPosePath, *pose); !s) return fail(engine::kExitBadInput, s.error().message);
    std::printf("%s\n", dumpPosePath.c_str());
    return 0;
  }

  const bool offscreen = !options.offscreen.empty();
  if (offscreen && options.run.screenshot.empty()) {
    std::filesystem::create_directories("out");
    options.run.screenshot = "out/viewer.png";
  }
  if (auto s = engine::finishCommonOptions(options, argc, argv); !s) {
    return fail(engine::kExitBadInput, s.error().message);
  }
  viewer::ViewerSettings settings;
  settings.clip = *clip;
  settings.speed = speed;
  settings.loop = loopMode;
  settings.skinMode = dualQuat ? engine::SkinMode::DualQuat : engine::SkinMode::Linear;
  settings.skeleton = skeleton;
  settings.variant = variantIndex;
  settings.camera = camera;
  settings.debugView = *view;
  settings.hdrTarget = engine::floatFormatForName(options.run.screenshot).has_value();
  // The scene renderer multisamples its own HDR target; the runner's target then
  // only receives the tone-mapped result.
  settings.msaa = options.run.msaa;
  options.run.targetSamples = 1;
  viewer::ViewerScene scene(options.shaderDir, std::move(model).value(), settings);

  const engine::Backend backend = engine::chosenBackend(options);
  if (backend == engine::Backend::Window && !engine::displayAvailable()) {
    return fail(engine::kExitBadInput, "no usable display; use --offscreen to render to a PNG");
  }
  const auto status = backend == engine::Backend::Window ? engine::runWindow(scene, options.run)
                                                         : engine::runHeadless(backend, scene, options.run);
  if (!status) return fail(engine::kExitBadInput, status.error().message);
  if (!options.run.screenshot.empty()) std::printf("%s\n", options.run.screenshot.c_str());
  return 0;
}
