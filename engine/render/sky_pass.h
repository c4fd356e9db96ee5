#pragma once
// The sky: drawn behind each view's opaque surfaces, and once at load into the
// environment cube that the PBR ambient's image-based lighting is built from
// (render/ibl.h). With the scene's atmosphere it is the planet's air, drawn from its
// tables (render/atmosphere_tables.h), and the cube is drawn again whenever they
// are rebuilt. Not part of the engine's interface.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/atmosphere_tables.h"
#include "render/ibl.h"
#include "render/scene_view.h"

namespace engine {

struct SceneStats;

class SkyPass {
 public:
  // The gradient's program, or the SKY_IMAGE variant's with `image` (the GPU
  // scene's), or the SKY_ATMOSPHERE variant's and its tables with an atmosphere;
  // none where the scene has neither sky nor atmosphere. `sun`: the scene's sun, if any (its
  // direction and disk). `displayDefines`: with direct output, what a second
  // program, for the view, writes display values with.
  static Result<std::unique_ptr<SkyPass>> create(const std::string& shaderDir, const SceneDesc& scene,
                                                 const LightDesc* sun, const gl::Texture& image,
                                                 const std::vector<std::string>& displayDefines, SceneStats* stats);
  // The PBR ambient's lighting from the environment (Ambient::Sh and ::Ibl only),
  // built once from a cube of `size` texels a face.
  Status buildEnvironment(const std::string& shaderDir, Ambient ambient, int size);
  const EnvironmentLighting* environment() const { return environment_ ? &*environment_ : nullptr; }

  // The atmosphere's tables, null without one.
  AtmosphereTables* atmosphere() const { return atmosphere_.get(); }
  // Brings the atmosphere's tables to the camera's place and the sun (the sky-view
  // table and then the environment where they moved; AtmosphereTables::update), and
  // the aerial-perspective volume to the camera's view (camera-relative).
  Status updateAtmosphere(const glm::dvec3& camera, const glm::mat4& viewProjection);
  // Turns the sun (toward it) for the next frames: the time of day.
  void setSunDirection(const glm::vec3& direction) { sunDirection_ = glm::normalize(direction); }

  // After the view's opaque surfaces, where they left the cleared far depth.
  void drawBehind(const View& view);
  // "sky(image name.hdr 2048x1024) ibl(...)": what exists of the sky and its
  // lighting ("" for neither).
  std::string describe() const;
  // "(built once in 12.3 ms)", where the environment's lighting was built.
  std::string describeEnvironmentCost() const;
  // The sky-view table's and the environment's last rebuild, GL work finished.
  double skyRebuildMs() const { return skyRebuildMs_; }
  double environmentRebuildMs() const { return environmentMs_; }

 private:
  SkyPass(const SceneDesc& scene, const gl::Texture& image, SceneStats* stats)
      : scene_(scene), image_(image), stats_(stats) {}
  void draw(const gl::Program& program, const glm::dmat4& viewProjection, bool sunDisk);
  bool drawsSky() const { return scene_.sky.enabled || atmosphere_; }
  // sky.frag's sun disk: its radiance at the centre through the air and the cosine
  // of its radius (SKY_ATMOSPHERE).
  glm::vec4 atmosphereSunDisk() const;

  const SceneDesc& scene_;
  const gl::Texture& image_;
  SceneStats* stats_;
  bool sun_ = false;
  glm::vec3 sunDirection_{0.0f, -1.0f, 0.0f};
  glm::vec3 sunPower_{0.0f};  // colour times intensity
  float sunAngleDegrees_ = 0.0f;
  std::unique_ptr<AtmosphereTables> atmosphere_;
  // program_: linear radiance (the HDR target, the environment cube);
  // displayProgram_: with direct output, the view's display values.
  gl::Program program_, displayProgram_;
  gl::VertexArray emptyVao_ = gl::VertexArray::create();
  Ambient ambient_ = Ambient::Hemisphere;
  std::optional<EnvironmentLighting> environment_;
  double environmentMs_ = 0.0;  // its one-time cost, GL work finished
  // What the environment is rebuilt with (with an atmosphere).
  std::string shaderDir_;
  int environmentSize_ = 0;
  double skyRebuildMs_ = 0.0;
};

}  // namespace engine
