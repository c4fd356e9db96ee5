#pragma once
// The glTF viewer's scene: one model, animated by a Player (clips, cross-fades,
// scrubbing, speed, loop modes), drawn by the scene renderer as every scene is,
// with its full metallic-roughness material and the sky's image-based light, on a
// ground under a sun with shadows; an optional skeleton overlay and an ImGui panel
// in the window. The model becomes a one-instance scene (scene/scene.h) whose
// pose the player sets each frame.
#include <memory>
#include <string>
#include <vector>

#include "app/game.h"
#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/camera.h"
#include "render/model_renderer.h"
#include "render/scene_renderer.h"
#include "scene/model_asset.h"

namespace viewer {

struct ViewerSettings {
  int clip = 0;  // -1: the rest pose
  double speed = 1.0;
  engine::LoopMode loop = engine::LoopMode::Repeat;
  engine::SkinMode skinMode = engine::SkinMode::Linear;
  bool skeleton = false;
  bool bindPose = false;
  int msaa = 1;
  // KHR_materials_variants: the variant drawn (-1: the file's default materials).
  int variant = -1;
  // The file's perspective camera to look through, placed by its node in the pose at
  // the first frame's time (-1: framed to the model's bounds).
  int camera = -1;
  // A debug view in place of the shaded image (render/scene_renderer.h).
  engine::DebugView debugView = engine::DebugView::None;
  // Where the camera looks from, toward the model's centre (framed to fit its
  // bounds). Golden tests of flat test models look straight at them (0, 0, 1), as
  // Khronos's screenshots do.
  glm::dvec3 viewDirection{0.45, 0.3, 1.0};
  // GPU culling (render.gpu_culling) for the one-model scene: the golden test of
  // culling draws the viewer's goldens with it on and off; the viewer has no flag.
  bool gpuCulling = false;
  // Keep the HDR target (SceneRenderOptions::hdrTarget) for a float screenshot.
  bool hdrTarget = false;
};

class ViewerScene final : public engine::Game {
 public:
  ViewerScene(std::string shaderDir, engine::ModelData model, ViewerSettings settings);
  ~ViewerScene() override;

  engine::Status init() override;
  void update(double time, double dt) override;
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override;
  bool wantsUi() const override { return true; }
  void drawUi() override;
  engine::Result<engine::FloatImage> linearFrame() override { return renderer_->readLinear(); }

  // The scene the model was placed in, and what the renderer built for it.
  const engine::SceneDesc& sceneDesc() const { return desc_; }
  std::string describe() const;

 private:
  struct Overlay;
  void frameCamera(const engine::ModelData& model);
  engine::Status buildRenderer();
  engine::Status showVariant(int variant);
  void drawSkeleton(const glm::mat4& viewProjection);
  void drawVariantPicker();
  void drawDebugViewPicker();
  void drawMaterialPanel();
  void placeAtModelCamera();

  std::string shaderDir_;
  std::shared_ptr<const engine::ModelAsset> asset_;  // as loaded: the player's
  // What the renderer draws: asset_, or a copy with a variant's materials.
  std::shared_ptr<const engine::ModelAsset> shown_;
  engine::ModelData model_;  // until init() makes the asset
  ViewerSettings settings_;
  engine::SceneDesc desc_;
  std::unique_ptr<engine::SceneRenderer> renderer_;
  std::unique_ptr<engine::Player> player_;
  std::vector<engine::Srt> locals_;
  engine::Pose pose_;
  int clip_ = -1;
  engine::Camera camera_;
  bool playing_ = true;
  bool started_ = false;
  std::unique_ptr<Overlay> overlay_;
  engine::Status posed_ = engine::Ok{};  // the last pose's
};

}  // namespace viewer
