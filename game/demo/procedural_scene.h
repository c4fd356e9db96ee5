#pragma once
// The demo's built-in scene until scene files drive the renderer: a tiled cube and
// a checkered sphere turning over a checkered ground, under a sun and a sky. The
// state is a pure function of time, so the frame at time T is the same however it
// was reached.
#include <memory>
#include <optional>
#include <string>

#include "app/game.h"
#include "gl/shader.h"
#include "render/lighting.h"
#include "render/mesh.h"

namespace demo {

struct SceneSettings {
  engine::Camera camera;
  glm::dvec3 cameraTarget{0.0, 0.8, 0.0};
  engine::Lighting lighting;
  // Where the whole scene sits in the world; far values test precision.
  glm::dvec3 origin{0.0};
};

// Reads the optional scene file: {"camera": {"position": [x,y,z], "target": [x,y,z],
// "fovy": deg}, "sun": {"direction": [x,y,z]}, "origin": [x,y,z]}. Errors name the
// file and the JSON path.
engine::Result<SceneSettings> loadSceneSettings(const std::string& path);
SceneSettings defaultSceneSettings();

class ProceduralScene final : public engine::Game {
 public:
  ProceduralScene(std::string shaderDir, std::string assetDir, SceneSettings settings);
  ~ProceduralScene() override;

  engine::Status init() override;
  void update(double time, double dt) override;
  void render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return settings_.camera; }
  void shutdown() override;

 private:
  struct Gpu;
  void drawSky(const glm::mat4& viewProjection) const;
  void drawObject(const engine::GpuMesh& mesh, const glm::dmat4& model, const glm::mat4& viewProjection,
                  int texture) const;

  void drawCharacters(const glm::mat4& viewProjection);

  std::string shaderDir_;
  std::string assetDir_;
  SceneSettings settings_;
  double time_ = 0.0;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace demo
