#include "render/sky_pass.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "asset/scene_file.h"
#include "gl/bindings.h"
#include "render/pass_state.h"
#include "render/scene_stats.h"

namespace engine {
namespace {

// The mean of the text's limb darkening over the sun's disk (area-weighted, the disk
// taken flat: it is half a degree), which the disk's radiance is divided by so that
// its irradiance stays the light's, as the path tracer's uniform disk gives it.
glm::vec3 meanLimbDarkening() {
  constexpr int kRings = 256;
  glm::vec3 sum(0.0f);
  for (int i = 0; i < kRings; ++i) {
    const float r = (float(i) + 0.5f) / kRings;
    sum += atmospheretext::sunLimbDarkening(r) * (2.0f * r / kRings);
  }
  return sum;
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// Linear (HDR_OUTPUT) for the HDR target and the environment cube, and with
// direct output a second that writes the view's display values.
Result<std::unique_ptr<SkyPass>> SkyPass::create(const std::string& shaderDir, const SceneDesc& scene,
                                                 const LightDesc* sun, const gl::Texture& image,
                                                 const std::vector<std::string>& displayDefines, SceneStats* stats) {
  std::unique_ptr<SkyPass> pass(new SkyPass(scene, image, stats));
  pass->sun_ = sun != nullptr;
  if (sun) {
    pass->sunDirection_ = glm::normalize(glm::vec3(sun->direction));
    pass->sunPower_ = sun->color * sun->intensity;
    pass->sunAngleDegrees_ = sun->angleDegrees;
  }
  if (scene.atmosphere.enabled) {
    auto tables = AtmosphereTables::create(shaderDir, scene.atmosphere);
    if (!tables) return tables.error();
    pass->atmosphere_ = std::move(tables).value();
    const auto start = std::chrono::steady_clock::now();
    pass->atmosphere_->update(pass->sunDirection_, std::numbers::pi_v<float> * pass->sunPower_,
                              scene.camera.position);
    glFinish();
    pass->skyRebuildMs_ = msSince(start);
  }
  if (!pass->drawsSky()) return pass;
  std::vector<std::string> variant;
  if (pass->atmosphere_) {
    variant.push_back("SKY_ATMOSPHERE 1");
  } else if (image) {
    variant.push_back("SKY_IMAGE 1");
  }
  const auto build = [&](std::vector<std::string> defines, gl::Program& out) -> Status {
    defines.insert(defines.end(), variant.begin(), variant.end());
    auto program = gl::Program::build(shaderDir, {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}}, defines);
    if (!program) return program.error();
    out = std::move(program).value();
    return Ok{};
  };
  if (auto s = build({"HDR_OUTPUT 1"}, pass->program_); !s) return s.error();
  if (!displayDefines.empty()) {
    if (auto s = build(displayDefines, pass->displayProgram_); !s) return s.error();
  }
  return pass;
}

// The environment as the path tracer sees it (the sky without its sun disk, or the
// background), drawn into a cube map once, or with an atmosphere again whenever its
// tables are rebuilt. From it the SH irradiance, the BRDF table and, for IBL, the
// prefiltered chain; the cube itself is dropped.
Status SkyPass::buildEnvironment(const std::string& shaderDir, Ambient ambient, int size) {
  ambient_ = ambient;
  shaderDir_ = shaderDir;
  environmentSize_ = size;
  const auto start = std::chrono::steady_clock::now();
  GLint callerFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &callerFramebuffer);
  const gl::Texture environment = makeCubeMap(size, 0);
  const gl::Framebuffer fbo = gl::Framebuffer::create();
  // Any 90-degree projection will do: sky.vert takes only directions from it.
  const glm::dmat4 projection = glm::perspective(glm::half_pi<double>(), 1.0, 0.1, 10.0);
  const glm::vec3 background = scene_.sky.background;
  glViewport(0, 0, size, size);
  applyPassState(kSkyPass);
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, environment.id(), 0, face);
    if (auto s = fbo.check("ibl-environment"); !s) return s;
    fbo.bind();
    glClearColor(background.r, background.g, background.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (drawsSky()) {
      draw(program_, projection * glm::lookAt(glm::dvec3(0.0), kCubeFaceDirections[face], kCubeFaceUps[face]), false);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(callerFramebuffer));
  applyPassState(kCallerState);
  environment.generateMipmaps();
  auto lighting = EnvironmentLighting::create(shaderDir, environment, size, ambient);
  if (!lighting) return makeError(scene_.path + ": /render/ambient: " + lighting.error().message);
  environment_ = std::move(lighting).value();
  glFinish();
  environmentMs_ = msSince(start);
  return Ok{};
}

Status SkyPass::updateAtmosphere(const glm::dvec3& camera, const glm::mat4& viewProjection) {
  const glm::vec3 illuminance = std::numbers::pi_v<float> * sunPower_;
  if (atmosphere_->stale(sunDirection_, illuminance, camera)) {
    glFinish();  // what the frame queued so far is not the rebuild's
    const auto start = std::chrono::steady_clock::now();
    atmosphere_->update(sunDirection_, illuminance, camera);
    glFinish();
    skyRebuildMs_ = msSince(start);
    if (environment_) {
      if (auto s = buildEnvironment(shaderDir_, ambient_, environmentSize_); !s) return s;
    }
  }
  atmosphere_->updateAerialPerspective(viewProjection);
  return Ok{};
}

glm::vec4 SkyPass::atmosphereSunDisk() const {
  if (!sun_ || sunAngleDegrees_ <= 0.0f) return glm::vec4(0.0f, 0.0f, 0.0f, 2.0f);  // no disk: no cosine passes 2
  const float half = glm::radians(sunAngleDegrees_) * 0.5f;
  // The path tracer's disk: uniform, I / sin^2(half), its irradiance pi I.
  const glm::vec3 uniform = sunPower_ / (std::sin(half) * std::sin(half));
  static const glm::vec3 mean = meanLimbDarkening();
  return glm::vec4(uniform / mean * atmosphere_->sunTransmittance(), std::cos(half));
}

void SkyPass::draw(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk) {
  program.use();
  if (atmosphere_) {
    atmosphere_->bindSky(program);
    program.set("u_sunDirection", sunDirection_);
    program.set("u_sunDisk", sunDisk ? atmosphereSunDisk() : glm::vec4(0.0f, 0.0f, 0.0f, 2.0f));
  } else if (image_) {
    const float radians = glm::radians(scene_.sky.rotationDegrees);
    program.set("u_skyIntensity", scene_.sky.intensity);
    program.set("u_skyRotation", glm::vec2(std::cos(radians), std::sin(radians)));
    image_.bind(gl::binding::kSkyImage);
  } else {
    // sky.frag's gradient (common/sky.glsl).
    program.set("u_sunDirection", glm::normalize(sunDirection_));
    program.set("u_skyColor", scene_.sky.zenith);
    program.set("u_horizonColor", scene_.sky.horizon);
    program.set("u_groundColor", scene_.sky.ground);
    program.set("u_sunDisk", sunDisk && sun_ && scene_.sky.sunDisk ? 1.0f : 0.0f);
  }
  program.set("u_inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++stats_->drawCalls;
}

// Shaded once a pixel instead of under every surface (on demo.json about half the
// screen), the same colour where it shows. Before the transmissive draws, which
// see it through their copy of the frame.
void SkyPass::drawBehind(const View& view) {
  if (!drawsSky()) return;
  applyPassState(kSkyBehindPass);
  draw(displayProgram_ ? displayProgram_ : program_, view.viewProjection, true);
}

std::string SkyPass::describe() const {
  std::ostringstream out;
  if (atmosphere_) {
    out << atmosphere_->describe() << atmosphere_->describeCost(skyRebuildMs_);
  } else if (scene_.sky.enabled) {
    out << "sky";
  }
  if (image_ && !atmosphere_) {
    out << "(image " << std::filesystem::path(scene_.sky.image).filename().string() << " " << image_.width() << "x"
        << image_.height() << ")";
  }
  if (environment_) {
    out << (drawsSky() ? " " : "") << ambientName(ambient_) << "(" << environment_->describe() << ")";
  }
  return out.str();
}

std::string SkyPass::describeEnvironmentCost() const {
  if (!environment_) return "";
  std::ostringstream out;
  out << " (built once in " << std::fixed << std::setprecision(1) << environmentMs_ << " ms)";
  return out.str();
}

}  // namespace engine
