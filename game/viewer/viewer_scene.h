#pragma once
// The animation viewer's scene: one glTF model, animated by a Player, skinned on
// the GPU (linear blend or dual quaternions), over a ground plane under the sky,
// with an optional skeleton overlay and an ImGui panel in the window.
#include <memory>
#include <string>
#include <vector>

#include "app/game.h"
#include "asset/model_data.h"
#include "render/character.h"
#include "render/lighting.h"

namespace viewer {

struct ViewerSettings {
  int clip = 0;  // -1: the rest pose
  double speed = 1.0;
  engine::LoopMode loop = engine::LoopMode::Repeat;
  engine::SkinMode skinMode = engine::SkinMode::Linear;
  bool skeleton = false;
  bool bindPose = false;
  // Where the camera looks from, toward the model's centre (framed to fit its
  // bounds). Golden tests of flat test models look straight at them (0, 0, 1), as
  // Khronos's screenshots do.
  glm::dvec3 viewDirection{0.45, 0.3, 1.0};
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

  // The shader variants built so far ("static", "lbs4", "dqs8", ...).
  std::vector<std::string> builtVariants() const;

 private:
  struct Gpu;
  void frameCamera(const engine::ModelData& model);
  void drawGround(const glm::mat4& viewProjection);
  void drawSkeleton(const glm::mat4& viewProjection);

  std::string shaderDir_;
  engine::ModelData model_;  // until init() moves it into the character asset
  ViewerSettings settings_;
  std::unique_ptr<engine::CharacterInstance> character_;
  engine::Camera camera_;
  engine::Lighting lighting_;
  bool playing_ = true;
  bool started_ = false;
  double groundHeight_ = 0.0;
  double groundSize_ = 10.0;
  double startTime_ = 0.0;
  std::unique_ptr<Gpu> gpu_;
  engine::Status posed_ = engine::Ok{};  // the last evaluate's
};

}  // namespace viewer
