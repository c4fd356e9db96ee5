#pragma once
// What a scene renderer uploads once from the scene layer (scene/scene.h): the
// scene file's shapes as meshes placed in the world, the materials' textures, the
// models and one character per instance, and the sky's image. Every pass draws from
// it. Where its characters are placed (eye()) is the origin of the camera-relative
// positions of whatever is drawn: the camera's, or a reflection probe's centre.
// Renderers of one scene whose options upload alike share it (the trade panel's
// rebuilds: SceneRenderer::create's `sharing`). Not part of the engine's interface.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/result.h"
#include "render/character.h"
#include "render/draw_items.h"
#include "render/mesh.h"
#include "scene/scene.h"

namespace engine {

struct SceneStats;

// A unit shape placed in the world, with a bounding sphere for culling
// (radius < 0: unbounded, never culled).
struct ShapeDraw {
  const GpuMesh* mesh = nullptr;
  glm::vec2 uvScale{1.0f};  // texture repeats across the shape
  glm::dmat4 world{1.0};
  int material = 0;
  glm::dvec3 center{0.0};
  double radius = -1.0;
  glm::dvec3 lo{0.0}, hi{0.0};  // world bounds: its mesh's, placed
  bool twoSided = false;
  int probe = -1;  // reflection probe of a mirror shape
};

// A scene instance (scene/scene.h) on the GPU: its pose is the scene's, copied in
// by takePoses; `world`, the bounds and the file's entry are the instance's.
struct CharacterDraw {
  std::unique_ptr<CharacterInstance> instance;
  glm::dmat4 world{1.0};
  ModelDesc desc;
  glm::dvec3 localCenter{0.0};
  double localRadius = 1.0;
};

inline SkinMode skinModeOf(const ModelDesc& desc) {
  return desc.unskinned ? SkinMode::None : desc.dualQuat ? SkinMode::DualQuat : SkinMode::Linear;
}

// How the scene is uploaded: the render settings that decide what its characters
// hold.
struct GpuSceneOptions {
  std::string shaderDir;
  Skinning skinning = Skinning::Auto;
  // A point light's cube shadow or reflection probes draw every caster many times
  // a frame: skinned characters then deform once, in the skin cache.
  bool manyPasses = false;
  bool levelsOfDetail = false;  // render.lod_pixels > 0
  std::optional<SkinMode> skinModeOverride;
  // The shape each reflection probe belongs to, in the probes' order (ShapeDraw::probe).
  std::vector<int> probeShapes;
  bool operator==(const GpuSceneOptions&) const = default;
};

class GpuScene {
 public:
  // Uploads `source`, whose description `scene` is (its lights included). Needs a
  // current context.
  static Result<std::unique_ptr<GpuScene>> create(std::shared_ptr<Scene> source, const SceneDesc& scene,
                                                  const GpuSceneOptions& options);
  const GpuSceneOptions& options() const { return options_; }

  Scene& source() const { return *source_; }
  const std::vector<ShapeDraw>& shapes() const { return shapes_; }
  // The shape meshes made (a sphere, a box, a plane's quad: those the scene has).
  std::vector<const GpuMesh*> meshes() const;
  bool isQuad(const GpuMesh* mesh) const { return mesh == quad_.get(); }
  // Empty where the material has none.
  const gl::Texture& materialTexture(int material) const { return materialTextures_[size_t(material)]; }
  std::vector<CharacterDraw>& characters() { return characters_; }
  const std::vector<CharacterDraw>& characters() const { return characters_; }
  // The sky's lat-long image (when the scene has one).
  const gl::Texture& skyImage() const { return skyImage_; }
  // The skin cache's compute programs: null where no instance uses the cache.
  SkinPrograms* skinPrograms() const { return skinPrograms_.get(); }
  // Some character primitive has a BLEND material; a transmissive one.
  bool blends() const { return blends_; }
  bool refracts() const { return refracts_; }

  // Each character takes its instance's pose from the scene (after Scene::update).
  void takePoses();
  void setPose(int instance, const Pose& pose);
  // Every character placed for a view from `eye`: only its root moves, the pose
  // (and its palettes) stay as the last pose left them.
  void place(const glm::dvec3& eye);
  const glm::dvec3& eye() const { return eye_; }
  void chooseLevelsOfDetail(const glm::dvec3& cameraPosition, double fovy, int height, double nearPlane,
                            double lodPixels);
  // The skin cache's pass: every character's pose deformed once, before any pass
  // draws it.
  Status deform(SceneStats& stats);

  // A character's bounding sphere (of every pose), placed: relative to eye(), its
  // radius grown by the placement's largest scale.
  std::pair<glm::dvec3, double> placedSphere(const CharacterDraw& c) const;
  // A shape's u_model, relative to eye(): the offset is taken in double, then the
  // matrix goes to float. GPU culling transforms its clusters by the same matrix.
  glm::mat4 shapeModel(const ShapeDraw& shape) const;
  // A draw item's triangles at full detail (an upper bound: a level of detail draws fewer).
  std::size_t triangles(const DrawItem& item) const;

  std::string describeSkinCache() const;
  std::string describeLevelsOfDetail(double lodPixels) const;

 private:
  Status loadModels(const SceneDesc& scene, const GpuSceneOptions& options);
  void addShapes(const SceneDesc& scene);

  std::shared_ptr<Scene> source_;
  GpuSceneOptions options_;
  std::unique_ptr<GpuMesh> sphere_, cube_, quad_;
  std::vector<ShapeDraw> shapes_;
  std::vector<gl::Texture> materialTextures_;  // empty texture = none
  gl::Texture skyImage_;
  // Declared before the characters, which point at it.
  std::unique_ptr<SkinPrograms> skinPrograms_;
  std::vector<CharacterDraw> characters_;
  bool blends_ = false, refracts_ = false;
  glm::dvec3 eye_{0.0};
};

}  // namespace engine
