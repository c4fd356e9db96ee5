#include "viewer_scene.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "anim/pose_dump.h"
#include "asset/material_variants.h"
#include "asset/model_lights.h"
#include "core/log.h"
#include "scene/scene.h"

namespace viewer {
using namespace engine;

// The skeleton's lines, drawn over the frame.
struct ViewerScene::Overlay {
  gl::Program lines;
  gl::VertexArray vao;
  gl::Buffer buffer;
};

namespace {

// The scene the viewer draws a model in: the sky (which lights it through the
// IBL), a checker ground under the model's lowest point and the model at the
// origin, lit by the model's own lights when it has any (as the Khronos Sample
// Viewer does: the file's lights replace its default ones; the scene's environment
// places them, scene/environment.h), else by a sun with shadows, as the viewer
// always had it.
SceneDesc viewerScene(const ModelData& model, const glm::dvec3& lo, double radius, const ViewerSettings& settings) {
  SceneDesc scene;
  scene.path = model.path;
  if (modelLights(model).empty()) {
    LightDesc sun;
    sun.direction = glm::normalize(glm::dvec3(0.5, 0.8, 0.3));
    sun.color = glm::vec3(1.0f, 0.94f, 0.85f);
    sun.intensity = 2.0f;
    sun.angleDegrees = 0.53f;
    scene.lights.push_back(sun);
  }
  MaterialDesc ground;
  ground.name = "ground";
  ground.color = glm::vec3(0.55f);
  ground.roughness = 0.9f;
  ground.texture = "checker";
  ground.textureScale = float(2.0 / radius);
  scene.materials.push_back(ground);
  PrimitiveDesc plane;
  plane.type = PrimitiveType::Plane;
  // A thousandth of the model's size below its lowest point: a model whose lowest
  // part is a flat floor (TwoSidedPlane) would otherwise share the ground's depth
  // and fight it; a gap that small is far below a pixel at the framing distance.
  plane.point = glm::dvec3(0.0, lo.y - 1e-3 * radius, 0.0);
  plane.extent = radius * 8.0;
  plane.material = 0;
  scene.primitives.push_back(plane);
  ModelDesc m;
  m.path = model.path;
  m.dualQuat = settings.skinMode == SkinMode::DualQuat;
  scene.models.push_back(m);
  scene.render.msaa = settings.msaa;
  return scene;
}

// The material panel's lines for one material: the core factors, then each glTF
// extension that moves it from the defaults, then the texture slots it fills.
void materialLines(const MaterialData& m) {
  const glm::vec4& c = m.baseColorFactor;
  ImGui::Text("base colour %.3g %.3g %.3g, alpha %.3g", c.r, c.g, c.b, c.a);
  ImGui::Text("metallic %.3g, roughness %.3g%s%s", m.metallicFactor, m.roughnessFactor,
              m.doubleSided ? ", double-sided" : "", m.unlit ? ", unlit" : "");
  if (m.alphaMode == AlphaMode::Mask) ImGui::Text("alpha mask below %.3g", m.alphaCutoff);
  else ImGui::Text("alpha %s", m.alphaMode == AlphaMode::Blend ? "blend" : "opaque");
  if (m.emissiveFactor != glm::vec3(0.0f))
    ImGui::Text("emissive %.3g %.3g %.3g", m.emissiveFactor.r, m.emissiveFactor.g, m.emissiveFactor.b);
  const MaterialLayers& l = m.layers;
  if (l.ior != 1.5f) ImGui::Text("ior %.3g", l.ior);
  if (l.specular != 1.0f || l.specularColor != glm::vec3(1.0f))
    ImGui::Text("specular %.3g, colour %.3g %.3g %.3g", l.specular, l.specularColor.r, l.specularColor.g,
                l.specularColor.b);
  if (l.clearcoat > 0.0f) ImGui::Text("clear coat %.3g, roughness %.3g", l.clearcoat, l.clearcoatRoughness);
  if (l.transmission > 0.0f) ImGui::Text("transmission %.3g", l.transmission);
  if (l.thickness > 0.0f)
    ImGui::Text("volume %.3g thick, %.3g %.3g %.3g after %.3g", l.thickness, l.attenuationColor.r,
                l.attenuationColor.g, l.attenuationColor.b, l.attenuationDistance);
  if (l.sheen())
    ImGui::Text("sheen %.3g %.3g %.3g, roughness %.3g", l.sheenColor.r, l.sheenColor.g, l.sheenColor.b,
                l.sheenRoughness);
  if (l.anisotropy > 0.0f) ImGui::Text("anisotropy %.3g, turned %.3g rad", l.anisotropy, l.anisotropyRotation);
  if (l.iridescence > 0.0f)
    ImGui::Text("iridescence %.3g, ior %.3g, %.0f-%.0f nm", l.iridescence, l.iridescenceIor, l.iridescenceThicknessMin,
                l.iridescenceThicknessMax);
  std::string textures;
  for (int i = 0; i < kTextureSlots; ++i)
    if (m.image(TextureSlot(i)) >= 0) textures += (textures.empty() ? "" : ", ") + std::string(textureSlotName(TextureSlot(i)));
  if (!textures.empty()) ImGui::TextWrapped("textures: %s", textures.c_str());
}

}  // namespace

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
  desc_ = viewerScene(model, glm::dvec3(lo), radius, settings_);
  desc_.camera.position = camera_.position;
  desc_.camera.forward = camera_.forward();
  desc_.camera.fovyDegrees = camera_.fovyDegrees;
  desc_.camera.nearPlane = camera_.nearPlane;
  desc_.camera.farPlane = camera_.farPlane;
}

// A new renderer over a new one-model scene (the skinning mode is the instance's):
// the model's data is shared, its GPU upload is not.
Status ViewerScene::buildRenderer() {
  desc_.models[0].dualQuat = settings_.skinMode == SkinMode::DualQuat;
  auto scene = Scene::load(desc_, {shown_});
  if (!scene) return scene.error();
  SceneRenderOptions options;
  options.shaderDir = shaderDir_;
  options.debugView = settings_.debugView;
  options.gpuCullingOverride = settings_.gpuCulling;
  options.hdrTarget = settings_.hdrTarget;
  auto renderer = SceneRenderer::create(std::move(scene).value(), options);
  if (!renderer) return renderer.error();
  renderer_ = std::move(renderer).value();
  renderer_->setPose(0, pose_);
  return Ok{};
}

Status ViewerScene::init() {
  auto asset = ModelAsset::create(std::move(model_));
  if (!asset) return asset.error();
  asset_ = std::move(asset).value();
  if (auto s = showVariant(settings_.variant); !s) return s;
  player_ = std::make_unique<Player>(asset_->animated.skeleton, asset_->animated.morphs.restWeights);
  clip_ = settings_.clip;
  if (clip_ >= 0 && clip_ < int(asset_->animated.clips.size())) player_->play(asset_->animated.clips[size_t(clip_)], settings_.loop);
  player_->setSpeed(settings_.speed);
  posed_ = playerPose(*asset_, *player_, true, locals_, pose_);
  if (auto s = buildRenderer(); !s) return s;
  auto overlay = std::make_unique<Overlay>();
  auto lines = gl::Program::build(shaderDir_, {{GL_VERTEX_SHADER, "lines.vert"}, {GL_FRAGMENT_SHADER, "lines.frag"}});
  if (!lines) return lines.error();
  overlay->lines = std::move(lines).value();
  // Two vertices (position, colour) per joint with a parent.
  const size_t joints = size_t(asset_->animated.skeleton.jointCount());
  overlay->buffer = gl::Buffer::create(std::max<size_t>(1, joints) * 2 * 2 * sizeof(glm::vec3));
  overlay->vao = gl::VertexArray::create();
  overlay->vao.vertexBuffer(0, overlay->buffer, 2 * sizeof(glm::vec3));
  overlay->vao.attribute(0, 0, 3, 0);
  overlay->vao.attribute(1, 0, 3, sizeof(glm::vec3));
  overlay_ = std::move(overlay);
  return Ok{};
}

// KHR_materials_variants: the model as `variant` dresses it (asset/material_variants.h);
// the animation stays the loaded asset's, which the variant does not change.
Status ViewerScene::showVariant(int variant) {
  settings_.variant = variant;
  if (variant < 0) {
    shown_ = asset_;
    return Ok{};
  }
  auto shown = ModelAsset::create(withVariant(asset_->model, variant));
  if (!shown) return shown.error();
  shown_ = std::move(shown).value();
  return Ok{};
}

// The file's camera settings_.camera (main.cpp has checked it) where its node
// stands in the pose: the view Khronos's screenshots of such models are taken from.
// The window's controls move the camera from there on.
void ViewerScene::placeAtModelCamera() {
  const ModelData& model = asset_->model;
  const int node = settings_.camera >= 0 ? cameraNode(model, settings_.camera) : -1;
  if (node < 0) return;
  const glm::dmat4 world(pose_.joints[size_t(asset_->animated.skeleton.jointOfRaw(node))]);
  const CameraData& c = model.cameras[size_t(settings_.camera)];
  camera_.position = glm::dvec3(world[3]);
  camera_.fovyDegrees = glm::degrees(double(c.yfov));
  camera_.nearPlane = c.znear;
  if (c.zfar > 0.0f) camera_.farPlane = c.zfar;
  camera_.lookAt(camera_.position - glm::normalize(glm::dvec3(world[2])));
}

void ViewerScene::shutdown() {
  overlay_.reset();
  renderer_.reset();
}

void ViewerScene::update(double time, double dt) {
  const bool first = !started_;
  if (first) {
    // The first update places the playhead at the scene time, so the frame at
    // time T shows the clip at T * speed whether or not frames came before.
    player_->seek(time * settings_.speed);
    started_ = true;
  } else if (playing_) {
    player_->update(dt);
  }
  // A failure ends the run at render.
  posed_ = playerPose(*asset_, *player_, settings_.bindPose || clip_ < 0, locals_, pose_);
  if (posed_) renderer_->setPose(0, pose_);
  if (posed_ && first) placeAtModelCamera();
}

void ViewerScene::drawSkeleton(const glm::mat4& viewProjection) {
  std::vector<glm::vec3> vertices;
  const auto parents = asset_->animated.skeleton.parents();
  for (size_t j = 0; j < pose_.joints.size(); ++j) {
    if (parents[j] < 0) continue;
    const glm::vec3 color = j % 2 ? glm::vec3(1.0f, 0.85f, 0.1f) : glm::vec3(1.0f, 0.4f, 0.1f);
    // Camera-relative, as the renderer draws: the model's root is the origin.
    vertices.push_back(glm::vec3(glm::dvec3(pose_.joints[j][3]) - camera_.position));
    vertices.push_back(color);
    vertices.push_back(glm::vec3(glm::dvec3(pose_.joints[size_t(parents[j])][3]) - camera_.position));
    vertices.push_back(color);
  }
  if (vertices.empty()) return;
  overlay_->buffer.upload(0, vertices.size() * sizeof(glm::vec3), vertices.data());
  overlay_->lines.use();
  overlay_->lines.set("u_viewProjection", viewProjection);
  overlay_->vao.bind();
  glDisable(GL_DEPTH_TEST);  // the skeleton is inside the skin: draw it on top
  glDrawArrays(GL_LINES, 0, GLsizei(vertices.size() / 2));
  glEnable(GL_DEPTH_TEST);
}

Status ViewerScene::render(const FrameInfo& frame) {
  if (!posed_) return posed_;
  if (auto s = renderer_->render(camera_, frame.width, frame.height); !s) return s;
  if (settings_.skeleton) {
    const double aspect = double(frame.width) / double(frame.height);
    drawSkeleton(camera_.projection(aspect) * camera_.rotationView());
  }
  return Ok{};
}

// KHR_materials_variants' picker: the file's default materials or one variant.
void ViewerScene::drawVariantPicker() {
  const std::vector<std::string>& variants = asset_->model.variants;
  if (variants.empty()) return;
  const std::string current = settings_.variant < 0 ? "(default)" : variants[size_t(settings_.variant)];
  if (!ImGui::BeginCombo("variant", current.c_str())) return;
  for (int v = -1; v < int(variants.size()); ++v) {
    if (!ImGui::Selectable(v < 0 ? "(default)" : variants[size_t(v)].c_str(), v == settings_.variant)) continue;
    const Status status = showVariant(v);
    posed_ = status ? buildRenderer() : status;  // a failure is shown as the run's error
  }
  ImGui::EndCombo();
}

// The debug views' picker: a new renderer with the view's program variants.
void ViewerScene::drawDebugViewPicker() {
  if (!ImGui::BeginCombo("debug view", debugViewName(settings_.debugView))) return;
  for (int v = 0; v <= int(DebugView::Alpha); ++v) {
    if (!ImGui::Selectable(debugViewName(DebugView(v)), DebugView(v) == settings_.debugView)) continue;
    settings_.debugView = DebugView(v);
    posed_ = buildRenderer();  // a failure is shown as the run's error
  }
  ImGui::EndCombo();
}

std::string ViewerScene::describe() const { return renderer_ ? renderer_->describe() : std::string(); }

void ViewerScene::drawUi() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Animation");
  const auto& clips = asset_->animated.clips;
  ImGui::Text("%s", asset_->model.path.c_str());
  ImGui::Text("%d joints, %zu clips", asset_->animated.skeleton.jointCount(), clips.size());
  if (ImGui::BeginListBox("clips", ImVec2(-1, 6 * ImGui::GetTextLineHeightWithSpacing()))) {
    for (int i = 0; i < int(clips.size()); ++i) {
      const Clip& clip = clips[size_t(i)];
      const std::string label = (clip.name().empty() ? "clip " + std::to_string(i) : clip.name()) + " (" +
                                std::to_string(clip.duration()).substr(0, 5) + " s)";
      if (ImGui::Selectable(label.c_str(), clip_ == i)) {
        if (player_->clip()) player_->crossFade(clip, 0.25, settings_.loop);
        else player_->play(clip, settings_.loop);
        clip_ = i;
      }
    }
    ImGui::EndListBox();
  }
  if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
  ImGui::SameLine();
  ImGui::Checkbox("bind pose", &settings_.bindPose);
  if (const Clip* clip = player_->clip()) {
    float t = float(player_->localTime());
    if (ImGui::SliderFloat("time", &t, 0.0f, float(std::max(clip->duration(), 1e-3)), "%.3f s")) player_->seek(t);
  }
  float speed = float(settings_.speed);
  if (ImGui::SliderFloat("speed", &speed, -2.0f, 2.0f, "%.2fx")) {
    settings_.speed = speed;
    player_->setSpeed(speed);
  }
  int loop = int(settings_.loop);
  const char* loops[] = {"repeat", "clamp", "ping-pong"};
  if (ImGui::Combo("loop", &loop, loops, 3) && player_->clip()) {
    settings_.loop = LoopMode(loop);
    const double time = player_->time();
    player_->play(*player_->clip(), settings_.loop);
    player_->seek(time);
  }
  int mode = int(settings_.skinMode);
  ImGui::RadioButton("LBS", &mode, int(SkinMode::Linear));
  ImGui::SameLine();
  ImGui::RadioButton("DQS", &mode, int(SkinMode::DualQuat));
  if (SkinMode(mode) != settings_.skinMode) {
    settings_.skinMode = SkinMode(mode);
    if (auto s = buildRenderer(); !s) posed_ = s;  // shown as the run's error
  }
  ImGui::Checkbox("skeleton", &settings_.skeleton);
  drawVariantPicker();
  drawDebugViewPicker();
  ImGui::End();
  drawMaterialPanel();
}

// The shown materials (the variant's, when one is picked), one section each.
void ViewerScene::drawMaterialPanel() {
  const std::vector<MaterialData>& materials = shown_->model.materials;
  if (materials.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(340, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Materials");
  for (size_t i = 0; i < materials.size(); ++i) {
    const std::string label = std::to_string(i) + ": " + (materials[i].name.empty() ? "(unnamed)" : materials[i].name);
    if (ImGui::CollapsingHeader(label.c_str(), i == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) materialLines(materials[i]);
  }
  ImGui::End();
}

}  // namespace viewer
