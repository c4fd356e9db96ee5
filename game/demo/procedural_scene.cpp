#include "procedural_scene.h"

#include <cmath>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "asset/gltf_loader.h"
#include "render/character.h"
#include "render/textures.h"

namespace demo {
using engine::Result;
using engine::makeError;

SceneSettings defaultSceneSettings() {
  SceneSettings s;
  s.camera.position = {3.0, 2.2, 4.4};
  s.camera.lookAt(s.cameraTarget);
  return s;
}

namespace {

Result<glm::dvec3> readVec3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) return makeError(where + ": expected an array of 3 numbers");
  glm::dvec3 v(0.0);
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) return makeError(where + "/" + std::to_string(i) + ": expected a number");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) return makeError(where + "/" + std::to_string(i) + ": not finite");
  }
  return v;
}

}  // namespace

Result<SceneSettings> loadSceneSettings(const std::string& path) {
  std::ifstream in(path);
  if (!in) return makeError(path + ": cannot open scene file");
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded()) return makeError(path + ": not valid JSON");
  if (!j.is_object()) return makeError(path + ": /: expected an object");
  SceneSettings s = defaultSceneSettings();
  if (j.contains("origin")) {
    auto v = readVec3(j["origin"], path + ": /origin");
    if (!v) return v.error();
    s.origin = *v;
  }
  if (j.contains("camera")) {
    const auto& c = j["camera"];
    if (!c.is_object()) return makeError(path + ": /camera: expected an object");
    if (c.contains("position")) {
      auto v = readVec3(c["position"], path + ": /camera/position");
      if (!v) return v.error();
      s.camera.position = *v;
    }
    if (c.contains("target")) {
      auto v = readVec3(c["target"], path + ": /camera/target");
      if (!v) return v.error();
      s.cameraTarget = *v;
    }
    if (c.contains("fovy")) {
      if (!c["fovy"].is_number() || c["fovy"].get<double>() <= 0.0 || c["fovy"].get<double>() >= 180.0) {
        return makeError(path + ": /camera/fovy: expected a number of degrees in (0, 180)");
      }
      s.camera.fovyDegrees = c["fovy"].get<double>();
    }
  }
  if (j.contains("sun")) {
    // value() throws on a non-object, so the type is checked first.
    if (!j["sun"].is_object()) return makeError(path + ": /sun: expected an object");
    auto v = readVec3(j["sun"].value("direction", nlohmann::json()), path + ": /sun/direction");
    if (!v) return v.error();
    // Scaled first: the length of (1e200, 0, 0) overflows to infinity.
    const glm::dvec3 d = *v / glm::max(glm::abs(v->x), glm::max(glm::abs(v->y), glm::abs(v->z)));
    if (!(glm::length(d) > 0.0)) return makeError(path + ": /sun/direction: must not be zero");
    s.lighting.sunDirection = glm::vec3(glm::normalize(d));
  }
  s.camera.position += s.origin;
  s.cameraTarget += s.origin;
  // Each value may be finite and the sum still overflow (origin 1e308 + position 1e308).
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(s.camera.position[i]) || !std::isfinite(s.cameraTarget[i]))
      return makeError(path + ": /origin: camera position or target plus the origin is not finite");
  s.camera.lookAt(s.cameraTarget);
  return s;
}

struct ProceduralScene::Gpu {
  engine::gl::Program lit;
  engine::gl::Program sky;
  engine::gl::VertexArray emptyVao;  // the sky's vertices come from gl_VertexID
  std::unique_ptr<engine::GpuMesh> ground, cube, sphere;
  engine::gl::Texture groundTexture, cubeTexture, sphereTexture;
  engine::ShaderVariants variants;
  std::vector<engine::CharacterInstance> robots;
  explicit Gpu(std::string shaderDir) : variants(std::move(shaderDir)) {}
};

namespace {
// The shipped robot: one walks a circle around the props, one waves beside them.
constexpr double kWalkRadius = 2.6;
constexpr double kWalkSpeed = 0.9;  // metres per second along the circle
}  // namespace

ProceduralScene::ProceduralScene(std::string shaderDir, std::string assetDir, SceneSettings settings)
    : shaderDir_(std::move(shaderDir)), assetDir_(std::move(assetDir)), settings_(std::move(settings)) {}

ProceduralScene::~ProceduralScene() = default;

engine::Status ProceduralScene::init() {
  auto gpu = std::make_unique<Gpu>(shaderDir_);
  auto lit = engine::gl::Program::build(
      shaderDir_, {{GL_VERTEX_SHADER, "lit.vert"}, {GL_FRAGMENT_SHADER, "lit.frag"}});
  if (!lit) return lit.error();
  auto sky = engine::gl::Program::build(
      shaderDir_, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}});
  if (!sky) return sky.error();
  gpu->lit = std::move(lit).value();
  gpu->sky = std::move(sky).value();
  gpu->emptyVao = engine::gl::VertexArray::create();
  gpu->ground = std::make_unique<engine::GpuMesh>(engine::makePlane(80.0f, 40, 40.0f));
  gpu->cube = std::make_unique<engine::GpuMesh>(engine::makeCube(1.2f));
  gpu->sphere = std::make_unique<engine::GpuMesh>(engine::makeSphere(0.6f, 32, 64));
  gpu->groundTexture =
      engine::uploadTexture(engine::makeChecker(256, 2, {200, 200, 190}, {60, 90, 50}), true);
  gpu->cubeTexture = engine::uploadTexture(engine::makeTiles(256, 4, {190, 90, 60}, {60, 50, 45}), true);
  gpu->sphereTexture =
      engine::uploadTexture(engine::makeChecker(256, 8, {230, 230, 240}, {50, 80, 160}), true);
  auto model = engine::loadGltf(assetDir_ + "/models/character.gltf");
  if (!model) return model.error();
  auto robot = engine::CharacterAsset::create(std::move(model).value());
  if (!robot) return robot.error();
  for (const char* clip : {"Walk", "Wave"}) {
    gpu->robots.emplace_back(*robot);
    auto index = engine::findClip(robot.value()->animated, clip, "character.gltf");
    if (!index) return index.error();
    gpu->robots.back().play(*index);
  }
  gpu_ = std::move(gpu);
  return engine::Ok{};
}

void ProceduralScene::shutdown() { gpu_.reset(); }

void ProceduralScene::update(double time, double) {
  time_ = time;
  // The clips are sampled at the scene time itself, so a frame depends on its time
  // only, never on how many frames came before it.
  for (auto& robot : gpu_->robots) {
    robot.player().seek(time);
    robot.evaluate();
  }
}

void ProceduralScene::drawCharacters(const glm::mat4& viewProjection) {
  const glm::dmat4 origin = glm::translate(glm::dmat4(1.0), settings_.origin);
  // Walker: along a circle, facing its direction of travel (the robot faces +z).
  const double angle = std::fmod(time_ * kWalkSpeed / kWalkRadius, glm::two_pi<double>());
  glm::dmat4 walker = glm::translate(origin, glm::dvec3(kWalkRadius * std::cos(angle), 0.0, -kWalkRadius * std::sin(angle)));
  walker = glm::rotate(walker, angle + glm::pi<double>(), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 waver = glm::rotate(glm::translate(origin, glm::dvec3(0.4, 0.0, -1.6)), 0.35, glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 transforms[] = {walker, waver};
  for (size_t i = 0; i < gpu_->robots.size(); ++i) {
    gpu_->robots[i].computeModels(transforms[i], settings_.camera.position);
    (void)gpu_->robots[i].draw(gpu_->variants, viewProjection, engine::SkinMode::Linear, settings_.lighting);
  }
}

void ProceduralScene::drawSky(const glm::mat4& viewProjection) const {
  const auto& sky = gpu_->sky;
  sky.use();
  sky.set("u_inverseViewProjection", glm::inverse(viewProjection));
  engine::setSkyUniforms(sky, settings_.lighting);
  gpu_->emptyVao.bind();
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

void ProceduralScene::drawObject(const engine::GpuMesh& mesh, const glm::dmat4& model,
                                 const glm::mat4& viewProjection, int texture) const {
  // Camera-relative: subtract the camera position in double, then go to float.
  glm::dmat4 relative = model;
  relative[3] -= glm::dvec4(settings_.camera.position, 0.0);
  const glm::mat4 m(relative);
  const auto& lit = gpu_->lit;
  lit.set("u_model", m);
  lit.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(m))));
  lit.set("u_viewProjection", viewProjection);
  const engine::gl::Texture* textures[] = {&gpu_->groundTexture, &gpu_->cubeTexture,
                                           &gpu_->sphereTexture};
  textures[texture]->bind(0);
  mesh.draw();
}

void ProceduralScene::render(const engine::FrameInfo& frame) {
  const double aspect = double(frame.width) / double(frame.height);
  const glm::mat4 viewProjection =
      settings_.camera.projection(aspect) * settings_.camera.rotationView();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  drawSky(viewProjection);

  const auto& lit = gpu_->lit;
  lit.use();
  engine::setLightingUniforms(lit, settings_.lighting);
  lit.set("u_baseColorFactor", glm::vec4(1.0f));
  lit.set("u_specular", 0.0f);
  lit.set("u_shininess", 16.0f);

  // Angles reduced in double first, so they stay exact at large times.
  const double spin = std::fmod(time_ * 0.8, glm::two_pi<double>());
  const double bob = std::sin(std::fmod(time_ * 2.0, glm::two_pi<double>()));
  const glm::dmat4 origin = glm::translate(glm::dmat4(1.0), settings_.origin);
  drawObject(*gpu_->ground, origin, viewProjection, 0);

  lit.set("u_specular", 0.25f);
  glm::dmat4 cube = glm::translate(origin, glm::dvec3(-0.9, 0.9 + 0.25 * bob, 0.0));
  cube = glm::rotate(cube, spin, glm::dvec3(0.3, 1.0, 0.2));
  drawObject(*gpu_->cube, cube, viewProjection, 1);

  lit.set("u_specular", 0.6f);
  lit.set("u_shininess", 64.0f);
  const glm::dvec3 orbit(1.3 + 0.4 * std::cos(spin), 0.6, 0.6 * std::sin(spin));
  glm::dmat4 sphere = glm::translate(origin, orbit);
  sphere = glm::rotate(sphere, -spin * 2.0, glm::dvec3(0.0, 1.0, 0.0));
  drawObject(*gpu_->sphere, sphere, viewProjection, 2);
  drawCharacters(viewProjection);
}

}  // namespace demo
