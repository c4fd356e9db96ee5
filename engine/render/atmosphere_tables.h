#pragma once
// The physically based sky's tables (Hillaire 2020, "A Scalable and Production Ready
// Sky and Atmosphere Rendering Technique"), built by compute passes
// (shaders/atmosphere/*.comp) from the scene's atmosphere (common/atmosphere.glsl,
// the path tracer's air): the transmittance (256 x 64) and multiple-scattering
// (32 x 32) tables once, as they depend on the air alone; the ground's sky
// irradiance and the sky-view table (192 x 108) when the sun or the camera's
// altitude moves; the aerial-perspective volume (32 x 32 x 32 froxels to 32 km)
// each frame, as it follows the view. Not part of the engine's interface.
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "core/atmosphere.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"

namespace engine {

// The air's transmittance from `altitude` (metres) along a direction at zenith
// cosine `mu` to the top of the air, 0 where the planet is in the way: the
// extinction of the shared text integrated in double precision (512 midpoint steps
// spaced by the square, as the table's 64). What the sun's light keeps on its way to
// a point; the table's reference in the tests.
glm::vec3 atmosphereTransmittance(const atmospheretext::Atmosphere& air, double altitude, double mu);

// Where a point of the scene is over the planet, whose surface passes through y = 0
// with its centre straight below the origin.
struct PlanetPlace {
  double altitude = 0.0;
  glm::dvec3 up{0.0, 1.0, 0.0};  // the local zenith
};
PlanetPlace planetPlace(const AtmosphereDesc& desc, const glm::dvec3& position);

class AtmosphereTables {
 public:
  // Builds the transmittance and multiple-scattering tables.
  static Result<std::unique_ptr<AtmosphereTables>> create(const std::string& shaderDir, const AtmosphereDesc& desc);

  // Rebuilds the ground's irradiance and the sky-view table where the sun (its
  // direction, toward it, and its illuminance: pi times colour times intensity)
  // or the camera's place has moved enough to show (its altitude by 1 m or 1 %,
  // the sun's zenith cosine there by 1e-4) since the last build. True when it did:
  // whatever is drawn from the sky (the environment cube) follows.
  bool update(const glm::vec3& sunDirection, const glm::vec3& sunIlluminance, const glm::dvec3& camera);
  // Whether update would rebuild.
  bool stale(const glm::vec3& sunDirection, const glm::vec3& sunIlluminance, const glm::dvec3& camera) const;
  // The aerial-perspective volume for the camera's view (camera-relative), where
  // the view or the sky-view table changed since the last.
  void updateAerialPerspective(const glm::mat4& viewProjection);

  // sky.frag's atmosphere variant: the sky-view table and where it was made from.
  void bindSky(const gl::Program& program) const;
  // The surfaces' aerial perspective (common/aerial_perspective.glsl).
  void bindAerialPerspective() const;
  // The sun's light reaching the camera's place: its transmittance there.
  glm::vec3 sunTransmittance() const { return sunTransmittance_; }

  const atmospheretext::Atmosphere& air() const { return air_; }
  const gl::Texture& transmittanceTable() const { return transmittance_; }
  const gl::Texture& skyViewTable() const { return skyView_; }
  int skyBuilds() const { return skyBuilds_; }
  int aerialBuilds() const { return aerialBuilds_; }
  // "atmosphere(transmittance 256x64, multi-scattering 32x32, sky-view 192x108,
  // aerial-perspective 32x32x32)".
  std::string describe() const;
  // " (built in 3.1 ms once, sky-view in 8.2 ms)": the air's tables at load, and
  // the sun's as `skyMs` measured them last.
  std::string describeCost(double skyMs) const;

 private:
  AtmosphereTables(const AtmosphereDesc& desc) : desc_(desc), air_(atmospheretext::atmosphereOf(desc)) {}
  Status build(const std::string& shaderDir);
  void setAir(const gl::Program& program) const;

  AtmosphereDesc desc_;
  atmospheretext::Atmosphere air_;
  gl::Program transmittanceProgram_, multiScatteringProgram_, groundProgram_, skyViewProgram_, aerialProgram_;
  gl::Texture transmittance_, multiScattering_, groundIrradiance_, skyView_, aerial_;
  // What the sky-view table was built for.
  bool built_ = false;
  glm::vec3 sunDirection_{0.0f}, sunIlluminance_{0.0f}, sunTransmittance_{1.0f};
  PlanetPlace place_;
  float muSun_ = 0.0f;
  int skyBuilds_ = 0;
  // What the aerial-perspective volume was built for.
  bool aerialBuilt_ = false;
  glm::mat4 aerialViewProjection_{1.0f};
  int aerialSkyBuild_ = 0, aerialBuilds_ = 0;
  double buildMs_ = 0.0;
};

}  // namespace engine
