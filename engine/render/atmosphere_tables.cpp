#include "render/atmosphere_tables.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "gl/bindings.h"

namespace engine {
namespace {

constexpr int kTransmittanceWidth = 256, kTransmittanceHeight = 64;  // atmosphere/lut.glsl's sizes
constexpr int kMultiScatteringSize = 32;
constexpr int kSkyViewWidth = 192, kSkyViewHeight = 108;
constexpr int kAerialSize = 32;

// A table read linearly between texels and clamped at its edges.
gl::Texture atmosphereTableTexture(GLenum target, GLenum format, int width, int height, int depth = 1) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  if (target == GL_TEXTURE_3D) {
    glTextureStorage3D(id, 1, format, width, height, depth);
  } else {
    glTextureStorage2D(id, 1, format, width, height);
  }
  gl::Texture table = gl::Texture::adopt(id, width, height);
  table.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  table.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  table.parameter(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  table.parameter(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  table.parameter(GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return table;
}

Result<gl::Program> atmosphereProgram(const std::string& shaderDir, const char* file) {
  return gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, file}});
}

// The distance from radius r along mu to the sphere of `radius` (r below it), in
// double: the test's geometry needs no care that the shaders' float does.
double distanceToSphere(double r, double mu, double radius) {
  return -r * mu + std::sqrt(std::max(0.0, radius * radius - r * r * (1.0 - mu * mu)));
}

}  // namespace

glm::vec3 atmosphereTransmittance(const atmospheretext::Atmosphere& air, double altitude, double mu) {
  const double bottom = air.bottomRadius, r = bottom + altitude;
  // The planet in the way: below the horizon of r.
  if (mu < 0.0 && r * r * (1.0 - mu * mu) < bottom * bottom) return glm::vec3(0.0f);
  const double length = distanceToSphere(r, mu, air.topRadius);
  constexpr int kSteps = 512;
  glm::dvec3 depth(0.0);
  double previous = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = double(i + 1) / kSteps, mid = (double(i) + 0.5) / kSteps;
    const double next = length * x * x, t = length * mid * mid;
    const double at = std::sqrt(r * r + t * t + 2.0 * r * t * mu) - bottom;
    depth += glm::dvec3(atmospheretext::atmosphereExtinction(air, atmospheretext::atmosphereDensities(air, float(at)))) *
             (next - previous);
    previous = next;
  }
  return glm::vec3(glm::exp(-depth));
}

PlanetPlace planetPlace(const AtmosphereDesc& desc, const glm::dvec3& position) {
  const glm::dvec3 fromCentre = position + glm::dvec3(0.0, desc.planetRadius, 0.0);
  const double r = glm::length(fromCentre);
  // r - R as (r^2 - R^2) / (r + R): y (2R + y) + x^2 + z^2 keeps a camera's 1.7 m.
  const double aboveGround2 = position.y * (2.0 * desc.planetRadius + position.y) + position.x * position.x +
                              position.z * position.z;
  return {aboveGround2 / (r + desc.planetRadius), fromCentre / r};
}

Result<std::unique_ptr<AtmosphereTables>> AtmosphereTables::create(const std::string& shaderDir,
                                                                   const AtmosphereDesc& desc) {
  std::unique_ptr<AtmosphereTables> tables(new AtmosphereTables(desc));
  if (auto s = tables->build(shaderDir); !s) return s.error();
  return tables;
}

void AtmosphereTables::setAir(const gl::Program& program) const {
  program.set("u_atmosphere.bottomRadius", air_.bottomRadius);
  program.set("u_atmosphere.topRadius", air_.topRadius);
  program.set("u_atmosphere.rayleighScattering", air_.rayleighScattering);
  program.set("u_atmosphere.rayleighScaleHeight", air_.rayleighScaleHeight);
  program.set("u_atmosphere.mieScattering", air_.mieScattering);
  program.set("u_atmosphere.mieAbsorption", air_.mieAbsorption);
  program.set("u_atmosphere.mieScaleHeight", air_.mieScaleHeight);
  program.set("u_atmosphere.mieAnisotropy", air_.mieAnisotropy);
  program.set("u_atmosphere.ozoneAbsorption", air_.ozoneAbsorption);
  program.set("u_atmosphere.ozoneCenter", air_.ozoneCenter);
  program.set("u_atmosphere.ozoneHalfWidth", air_.ozoneHalfWidth);
  program.set("u_atmosphere.groundAlbedo", air_.groundAlbedo);
}

// The programs, the tables, and the two that depend on the air alone.
Status AtmosphereTables::build(const std::string& shaderDir) {
  const std::pair<gl::Program*, const char*> programs[] = {
      {&transmittanceProgram_, "atmosphere/transmittance.comp"},
      {&multiScatteringProgram_, "atmosphere/multi_scattering.comp"},
      {&groundProgram_, "atmosphere/ground_irradiance.comp"},
      {&skyViewProgram_, "atmosphere/sky_view.comp"},
      {&aerialProgram_, "atmosphere/aerial_perspective.comp"}};
  for (const auto& [program, file] : programs) {
    auto built = atmosphereProgram(shaderDir, file);
    if (!built) return built.error();
    *program = std::move(built).value();
    setAir(*program);
  }
  transmittance_ = atmosphereTableTexture(GL_TEXTURE_2D, GL_RGBA32F, kTransmittanceWidth, kTransmittanceHeight);
  multiScattering_ = atmosphereTableTexture(GL_TEXTURE_2D, GL_RGBA32F, kMultiScatteringSize, kMultiScatteringSize);
  groundIrradiance_ = atmosphereTableTexture(GL_TEXTURE_2D, GL_RGBA32F, 1, 1);
  skyView_ = atmosphereTableTexture(GL_TEXTURE_2D, GL_RGBA32F, kSkyViewWidth, kSkyViewHeight);
  aerial_ = atmosphereTableTexture(GL_TEXTURE_3D, GL_RGBA16F, kAerialSize, kAerialSize, 2 * kAerialSize);

  const auto start = std::chrono::steady_clock::now();
  transmittanceProgram_.use();
  glBindImageTexture(gl::binding::kSkyTableImage, transmittance_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(GLuint(kTransmittanceWidth / 8), GLuint(kTransmittanceHeight / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  multiScatteringProgram_.use();
  transmittance_.bind(gl::binding::kSkyTransmittance);
  glBindImageTexture(gl::binding::kSkyTableImage, multiScattering_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(GLuint(kMultiScatteringSize), GLuint(kMultiScatteringSize), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glFinish();
  buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return Ok{};
}

bool AtmosphereTables::stale(const glm::vec3& sunDirection, const glm::vec3& sunIlluminance,
                             const glm::dvec3& camera) const {
  const PlanetPlace place = planetPlace(desc_, camera);
  const float muSun = float(glm::dot(glm::dvec3(sunDirection), place.up));
  const bool moved = std::abs(place.altitude - place_.altitude) > std::max(1.0, 0.01 * place_.altitude) ||
                     std::abs(muSun - muSun_) > 1e-4f;
  return !built_ || moved || sunDirection != sunDirection_ || sunIlluminance != sunIlluminance_;
}

bool AtmosphereTables::update(const glm::vec3& sunDirection, const glm::vec3& sunIlluminance,
                              const glm::dvec3& camera) {
  if (!stale(sunDirection, sunIlluminance, camera)) return false;
  const PlanetPlace place = planetPlace(desc_, camera);
  const float muSun = float(glm::dot(glm::dvec3(sunDirection), place.up));
  built_ = true;
  sunDirection_ = sunDirection;
  sunIlluminance_ = sunIlluminance;
  place_ = place;
  muSun_ = muSun;
  sunTransmittance_ = atmosphereTransmittance(air_, place.altitude, muSun);

  transmittance_.bind(gl::binding::kSkyTransmittance);
  multiScattering_.bind(gl::binding::kSkyMultiScattering);
  groundProgram_.use();
  groundProgram_.set("u_muSun", muSun);
  glBindImageTexture(gl::binding::kSkyTableImage, groundIrradiance_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  skyViewProgram_.use();
  skyViewProgram_.set("u_altitude", float(place.altitude));
  skyViewProgram_.set("u_muSun", muSun);
  skyViewProgram_.set("u_sunIlluminance", sunIlluminance);
  groundIrradiance_.bind(gl::binding::kSkyGroundIrradiance);
  glBindImageTexture(gl::binding::kSkyTableImage, skyView_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(GLuint((kSkyViewWidth + 7) / 8), GLuint((kSkyViewHeight + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  ++skyBuilds_;
  return true;
}

void AtmosphereTables::updateAerialPerspective(const glm::mat4& viewProjection) {
  // A still camera under a still sun keeps its volume (2.5 ms a frame on llvmpipe).
  if (aerialBuilt_ && viewProjection == aerialViewProjection_ && aerialSkyBuild_ == skyBuilds_) return;
  aerialBuilt_ = true;
  aerialViewProjection_ = viewProjection;
  aerialSkyBuild_ = skyBuilds_;
  ++aerialBuilds_;
  aerialProgram_.use();
  aerialProgram_.set("u_inverseViewProjection", glm::inverse(viewProjection));
  aerialProgram_.set("u_up", glm::vec3(place_.up));
  aerialProgram_.set("u_sunDirection", sunDirection_);
  aerialProgram_.set("u_altitude", float(place_.altitude));
  aerialProgram_.set("u_sunIlluminance", sunIlluminance_);
  transmittance_.bind(gl::binding::kSkyTransmittance);
  multiScattering_.bind(gl::binding::kSkyMultiScattering);
  glBindImageTexture(gl::binding::kSkyTableImage, aerial_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glDispatchCompute(GLuint(kAerialSize / 8), GLuint(kAerialSize / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void AtmosphereTables::bindSky(const gl::Program& program) const {
  setAir(program);
  program.set("u_up", glm::vec3(place_.up));
  program.set("u_altitude", float(place_.altitude));
  skyView_.bind(gl::binding::kSkyView);
}

void AtmosphereTables::bindAerialPerspective() const { aerial_.bind(gl::binding::kAerialPerspective); }

std::string AtmosphereTables::describe() const {
  std::ostringstream out;
  out << "atmosphere(transmittance " << kTransmittanceWidth << "x" << kTransmittanceHeight << ", multi-scattering "
      << kMultiScatteringSize << "x" << kMultiScatteringSize << ", sky-view " << kSkyViewWidth << "x" << kSkyViewHeight
      << ", aerial-perspective " << kAerialSize << "x" << kAerialSize << "x" << kAerialSize << ")";
  return out.str();
}

std::string AtmosphereTables::describeCost(double skyMs) const {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << " (built in " << buildMs_ << " ms once, sky-view in " << skyMs
      << " ms)";
  return out.str();
}

}  // namespace engine
