#pragma once
// Animated glTF characters: the shared, read-only asset (model data, skeleton and
// clips, GPU buffers) and per-instance state (player, pose, skin palettes), so
// that many instances of one model cost one upload.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anim/model_builder.h"
#include "anim/player.h"
#include "asset/model_data.h"
#include "render/model_renderer.h"
#include "render/skin_cache.h"
#include "scene/model_asset.h"

namespace engine {

// A model asset (scene/model_asset.h) on the GPU. `model` and `animated` are the
// source's, named here for the many places that read them.
struct CharacterAsset {
  std::shared_ptr<const ModelAsset> source;
  const ModelData& model;
  const AnimatedModel& animated;
  GpuModel gpu;

  // Uploads the model (needs a context), with its levels of detail when asked
  // (ModelAsset::levelsOfDetail, made here).
  static Result<std::shared_ptr<const CharacterAsset>> create(std::shared_ptr<const ModelAsset> source,
                                                              bool levelsOfDetail = false);
  // ModelAsset::create, then the upload.
  static Result<std::shared_ptr<const CharacterAsset>> create(ModelData model);
  using Bounds = ModelAsset::Bounds;
  Result<Bounds> boundsOfAllPoses(int samples = 24) const { return source->boundsOfAllPoses(samples); }
};

class CharacterInstance {
 public:
  explicit CharacterInstance(std::shared_ptr<const CharacterAsset> asset);

  // Plays `clip` (-1: rest pose) from clip time `start`.
  void play(int clip, LoopMode mode = LoopMode::Repeat, double start = 0.0);
  void crossFade(int clip, double seconds);
  Player& player() { return player_; }
  int clip() const { return clip_; }

  // Samples the pose at the player's time (the rest pose when `bindPose`): the
  // joints in model space, once per pose however many views draw it.
  Status evaluate(bool bindPose = false);
  // Takes a pose made elsewhere (a Scene's instance, scene/scene.h) instead.
  void setPose(const Pose& pose);
  // Places the posed model for one view: its root `world` relative to
  // `cameraPosition`, composed in double so that characters far from the origin
  // stay precise. Touches no joint: the palettes stay in model space and the root
  // reaches the shader as its model matrix.
  void place(const glm::dmat4& world, const glm::dvec3& cameraPosition);
  // The error every later draw's levels of detail may have, as MeshLod::error states
  // it (ModelFrame::lodBudget); 0, the default, draws every mesh in full.
  void setLodBudget(float budget) { lodBudget_ = budget; }
  // From now on deforms through a skin cache (render/skin_cache.h) with
  // `programs`, which must outlive the instance; nullptr goes back to skinning in
  // each pass's vertex shader.
  void useSkinCache(SkinPrograms* programs);
  const SkinCache* skinCache() const { return cache_ ? &*cache_ : nullptr; }
  // Uploads the pose's skin palettes and morph weights and, with a skin cache,
  // deforms: once per pose and mode, however many passes draw it (every draw
  // calls it; a renderer calls it first to time it on its own).
  Status prepare(SkinMode mode);
  // Uploads the skin palettes (once per pose) and draws every primitive;
  // without `includeBlend` the BLEND ones are left for drawBlend.
  // `setUniforms` sets the program's lights and shadows.
  Status draw(ShaderVariants& variants, SkinMode mode,
              const std::function<void(const gl::Program&)>& setUniforms, bool depthOnly = false,
              bool includeBlend = true);
  // The BLEND primitives and their distances from the camera of the last
  // place, for a scene to sort with those of other models.
  std::vector<BlendPrimitive> blendPrimitives() const;
  Status drawBlend(ShaderVariants& variants, SkinMode mode,
                   const std::function<void(const gl::Program&)>& setUniforms, const BlendPrimitive& primitive,
                   std::span<const IndirectDraw> indirect = {});
  // How drawPrimitive draws: ModelFrame's members of the same names (indirect:
  // GPU culling's commands).
  struct PrimitivePass {
    bool depthOnly = false;
    bool nearSunOnly = false;
    ShaderVariant::Surface surface = ShaderVariant::Surface::None;
    std::span<const IndirectDraw> indirect;
  };
  // One primitive, in whatever pass state the caller set (a scene's draw items).
  Status drawPrimitive(ShaderVariants& variants, SkinMode mode,
                       const std::function<void(const gl::Program&)>& setUniforms, int node, int primitive,
                       const PrimitivePass& pass);
  // The u_model of each instance of node `node`'s primitives with `influences`
  // joints, placed for the last place() view (primitiveInstanceModels).
  std::vector<glm::mat4> instanceModels(SkinMode mode, int node, int influences) const;
  float lodBudget() const { return lodBudget_; }

  // The joints of the pose in model space, and placed for the last place() view.
  std::span<const glm::mat4> models() const { return pose_.joints; }
  std::vector<glm::mat4> placedJoints() const;
  // The morph weights of the last evaluate(), in the asset's MorphLayout order.
  std::span<const float> morphWeights() const { return pose_.morphWeights; }
  const CharacterAsset& asset() const { return *asset_; }

 private:
  Status uploadPalettes(SkinMode mode);
  void uploadMorphWeights();
  Result<ModelFrame> frame(SkinMode mode,
                   const std::function<void(const gl::Program&)>& setUniforms);

  std::shared_ptr<const CharacterAsset> asset_;
  Player player_;
  int clip_ = -1;
  std::vector<Srt> locals_;
  Pose pose_;  // joints per runtime joint in model space; morph weights in MorphLayout order
  glm::dmat4 root_{1.0};               // the model's root, camera-relative (place)
  std::vector<glm::mat4> nodeWorlds_;  // per glTF node, camera-relative (place)
  std::vector<glm::mat4> palette_;     // scratch, reused every frame
  std::vector<glm::vec4> paletteRows_;  // scratch: palette_ as the shaders read it
  std::vector<DualQuat> dualQuats_;    // scratch
  std::vector<gl::Buffer> skinBuffers_;
  std::vector<gl::Texture> skinPalettes_;  // each of skinBuffers_ as shaders read it
  gl::Buffer morphBuffer_;           // the same on the GPU
  SkinPrograms* skinPrograms_ = nullptr;
  std::optional<SkinCache> cache_;
  float lodBudget_ = 0.0f;
  bool palettesCurrent_ = false;  // palettes and weights uploaded (and deformed) since the last pose
  SkinMode uploadedMode_ = SkinMode::Linear;
};

}  // namespace engine
