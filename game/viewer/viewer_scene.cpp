#include "viewer_scene.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/bindings.h"
#include "anim/jobs.h"
#include "anim/pose_dump.h"
#include "render/mesh.h"
#include "render/textures.h"

namespace viewer {
using namespace engine;

struct ViewerScene::Gpu {
  ShaderVariants variants;
  gl::Program sky;
  gl::Program lines;
  gl::VertexArray emptyVao;
  gl::VertexArray lineVao;
  gl::Buffer lineBuffer;
  std::unique_ptr<GpuMesh> ground;
  gl::Texture groundTexture;
  explicit Gpu(std::string shaderDir) : variants(std::move(shaderDir)) {}
};

ViewerScene::ViewerScene(std::string shaderDir, ModelData model, ViewerSettings settings)
    : shaderDir_(std::move(shaderDir)), model_(std::move(model)), settings_(settings) {
  frameCamera(model_);
}

ViewerScene::~ViewerScene() = default;

void ViewerScene::frameCamera(const ModelData& model) {
  // Bounds of the posed, skinned vertices: the same numbers --dump-pose writes.
  auto pose = dumpPose(model, -1, 0.0);
  glm::vec3 lo(1e30f), hi(-1e30f);
  if (pose) {
    for (const auto& mesh : (*pose)["meshes"]) {
      const auto& p = mesh["positions"];
      for (size_t i = 0; i + 2 < p.size(); i += 3) {
        const glm::vec3 v(p[i].get<float>(), p[i + 1].get<float>(), p[i + 2].get<float>());
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
    }
  }
  if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
  const glm::dvec3 center = glm::dvec3(lo + hi) * 0.5;
  const double radius = std::max(1e-3, 0.5 * double(glm::length(hi - lo)));
  const double distance = radius / std::sin(glm::radians(camera_.fovyDegrees) * 0.5) * 1.1;
  camera_.position = center + glm::normalize(settings_.viewDirection) * distance;
  camera_.nearPlane = distance / 100.0;
  camera_.farPlane = distance * 100.0;
  camera_.lookAt(center);
  groundHeight_ = lo.y;
  groundSize_ = radius * 8.0;
  lighting_.fogDensity = float(0.15 / distance);
}

Status ViewerScene::init() {
  auto gpu = std::make_unique<Gpu>(shaderDir_);
  auto asset = CharacterAsset::create(std::move(model_));
  if (!asset) return asset.error();
  character_ = std::make_unique<CharacterInstance>(std::move(asset).value());
  character_->play(settings_.clip, settings_.loop);
  character_->player().setSpeed(settings_.speed);
  auto sky = gl::Program::build(shaderDir_, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}});
  if (!sky) return sky.error();
  auto lines = gl::Program::build(shaderDir_, {{GL_VERTEX_SHADER, "lines.vert"}, {GL_FRAGMENT_SHADER, "lines.frag"}});
  if (!lines) return lines.error();
  gpu->sky = std::move(sky).value();
  gpu->lines = std::move(lines).value();
  gpu->emptyVao = gl::VertexArray::create();
  // Two vertices (position, colour) per joint with a parent.
  const size_t joints = size_t(character_->asset().animated.skeleton.jointCount());
  gpu->lineBuffer = gl::Buffer::create(std::max<size_t>(1, joints) * 2 * 2 * sizeof(glm::vec3));
  gpu->lineVao = gl::VertexArray::create();
  gpu->lineVao.vertexBuffer(0, gpu->lineBuffer, 2 * sizeof(glm::vec3));
  gpu->lineVao.attribute(0, 0, 3, 0);
  gpu->lineVao.attribute(1, 0, 3, sizeof(glm::vec3));
  gpu->ground = std::make_unique<GpuMesh>(makePlane(float(groundSize_), 8, 16.0f));
  gpu->groundTexture = uploadTexture(makeChecker(128, 2, {170, 170, 165}, {120, 125, 120}), true);
  gpu_ = std::move(gpu);
  return Ok{};
}

void ViewerScene::shutdown() {
  gpu_.reset();
  character_.reset();
}

void ViewerScene::update(double time, double dt) {
  Player& player = character_->player();
  if (!started_) {
    // The first update places the playhead at the scene time, so the frame at
    // time T shows the clip at T * speed whether or not frames came before.
    player.seek(time * settings_.speed);
    started_ = true;
  } else if (playing_) {
    player.update(dt);
  }
  posed_ = character_->evaluate(settings_.bindPose);  // a failure ends the run at render
}

void ViewerScene::drawGround(const glm::mat4& viewProjection) {
  auto program = gpu_->variants.get({0, SkinMode::Linear, true});  // textured: the checker
  if (!program) return;
  const gl::Program& pr = **program;
  pr.use();
  setLightingUniforms(pr, lighting_);
  const glm::dvec3 offset = glm::dvec3(0.0, groundHeight_, 0.0) - camera_.position;
  const glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(offset));
  pr.set("u_model", m);
  pr.set("u_normalMatrix", glm::mat3(1.0f));
  pr.set("u_viewProjection", viewProjection);
  pr.set("u_baseColorFactor", glm::vec4(1.0f));
  pr.set("u_specular", 0.0f);
  pr.set("u_shininess", 16.0f);
  gpu_->groundTexture.bind(gl::binding::kBaseColor);
  gpu_->ground->draw();
}

void ViewerScene::drawSkeleton(const glm::mat4& viewProjection) {
  std::vector<glm::vec3> vertices;
  const auto parents = character_->asset().animated.skeleton.parents();
  const auto models = character_->placedJoints();  // camera-relative
  for (size_t j = 0; j < models.size(); ++j) {
    if (parents[j] < 0) continue;
    const glm::vec3 color = j % 2 ? glm::vec3(1.0f, 0.85f, 0.1f) : glm::vec3(1.0f, 0.4f, 0.1f);
    vertices.push_back(glm::vec3(models[j][3]));
    vertices.push_back(color);
    vertices.push_back(glm::vec3(models[size_t(parents[j])][3]));
    vertices.push_back(color);
  }
  if (vertices.empty()) return;
  gpu_->lineBuffer.upload(0, vertices.size() * sizeof(glm::vec3), vertices.data());
  gpu_->lines.use();
  gpu_->lines.set("u_viewProjection", viewProjection);
  gpu_->lineVao.bind();
  glDisable(GL_DEPTH_TEST);  // the skeleton is inside the skin: draw it on top
  glDrawArrays(GL_LINES, 0, GLsizei(vertices.size() / 2));
  glEnable(GL_DEPTH_TEST);
}

Status ViewerScene::render(const FrameInfo& frame) {
  const double aspect = double(frame.width) / double(frame.height);
  const glm::mat4 viewProjection = camera_.projection(aspect) * camera_.rotationView();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);

  gpu_->sky.use();
  setSkyUniforms(gpu_->sky, lighting_);
  gpu_->sky.set("u_inverseViewProjection", glm::inverse(viewProjection));
  gpu_->emptyVao.bind();
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);

  drawGround(viewProjection);
  if (!posed_) return posed_;
  character_->place(glm::dmat4(1.0), camera_.position);
  if (auto s = character_->draw(gpu_->variants, viewProjection, settings_.skinMode, lighting_); !s) return s;
  if (settings_.skeleton) drawSkeleton(viewProjection);
  return Ok{};
}

std::vector<std::string> ViewerScene::builtVariants() const {
  std::vector<std::string> out;
  if (gpu_)
    for (const auto& v : gpu_->variants.built()) out.push_back(v.describe());
  return out;
}

void ViewerScene::drawUi() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Animation");
  const CharacterAsset& asset = character_->asset();
  Player& player = character_->player();
  ImGui::Text("%s", asset.model.path.c_str());
  ImGui::Text("%d joints, %zu clips", asset.animated.skeleton.jointCount(), asset.animated.clips.size());
  if (ImGui::BeginListBox("clips", ImVec2(-1, 6 * ImGui::GetTextLineHeightWithSpacing()))) {
    for (int i = 0; i < int(asset.animated.clips.size()); ++i) {
      const Clip& clip = asset.animated.clips[size_t(i)];
      const std::string label = (clip.name().empty() ? "clip " + std::to_string(i) : clip.name()) +
                                " (" + std::to_string(clip.duration()).substr(0, 5) + " s)";
      if (ImGui::Selectable(label.c_str(), character_->clip() == i)) character_->crossFade(i, 0.25);
    }
    ImGui::EndListBox();
  }
  if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
  ImGui::SameLine();
  ImGui::Checkbox("bind pose", &settings_.bindPose);
  if (const Clip* clip = player.clip()) {
    float t = float(player.localTime());
    if (ImGui::SliderFloat("time", &t, 0.0f, float(std::max(clip->duration(), 1e-3)), "%.3f s")) {
      player.seek(t);
      posed_ = character_->evaluate(settings_.bindPose);
    }
  }
  float speed = float(settings_.speed);
  if (ImGui::SliderFloat("speed", &speed, -2.0f, 2.0f, "%.2fx")) {
    settings_.speed = speed;
    player.setSpeed(speed);
  }
  int loop = int(settings_.loop);
  const char* loops[] = {"repeat", "clamp", "ping-pong"};
  if (ImGui::Combo("loop", &loop, loops, 3)) {
    settings_.loop = LoopMode(loop);
    character_->play(character_->clip(), settings_.loop, player.time());
  }
  int mode = int(settings_.skinMode);
  ImGui::RadioButton("LBS", &mode, int(SkinMode::Linear));
  ImGui::SameLine();
  ImGui::RadioButton("DQS", &mode, int(SkinMode::DualQuat));
  settings_.skinMode = SkinMode(mode);
  ImGui::Checkbox("skeleton", &settings_.skeleton);
  ImGui::End();
}

}  // namespace viewer
