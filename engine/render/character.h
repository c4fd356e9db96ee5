#pragma once
// Animated glTF characters: the shared, read-only asset (model data, skeleton and
// clips, GPU buffers) and per-instance state (player, pose, skin palettes), so
// that many instances of one model cost one upload.
#include <memory>
#include <string>
#include <vector>

#include "anim/model_builder.h"
#include "anim/player.h"
#include "asset/model_data.h"
#include "render/model_renderer.h"

namespace engine {

struct CharacterAsset {
  ModelData model;
  AnimatedModel animated;
  GpuModel gpu;

  // Builds the runtime animation data and uploads the model (needs a context).
  static Result<std::shared_ptr<const CharacterAsset>> create(ModelData model);
  // Model-space bounds that hold every pose of every clip (sampled `samples`
  // times per clip, and the rest pose), for culling skinned meshes.
  struct Bounds {
    glm::vec3 min{0.0f}, max{0.0f};
  };
  Result<Bounds> boundsOfAllPoses(int samples = 24) const;
};

class CharacterInstance {
 public:
  explicit CharacterInstance(std::shared_ptr<const CharacterAsset> asset);

  // Plays `clip` (-1: rest pose) from clip time `start`.
  void play(int clip, LoopMode mode = LoopMode::Repeat, double start = 0.0);
  void crossFade(int clip, double seconds);
  Player& player() { return player_; }
  int clip() const { return clip_; }

  // Samples the pose at the player's time (the rest pose when `bindPose`).
  void evaluate(bool bindPose = false);
  // Joint matrices relative to the camera: root = camera offset * `transform`,
  // composed in double so that characters far from the origin stay precise.
  Status computeModels(const glm::dmat4& transform, const glm::dvec3& cameraPosition);
  // Uploads the skin palettes (once per computeModels) and draws every primitive;
  // without `includeBlend` the BLEND ones are left for drawBlend.
  // `setUniforms` sets the program's lights and shadows.
  Status draw(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
              const std::function<void(const gl::Program&)>& setUniforms, bool depthOnly = false,
              bool includeBlend = true);
  // The BLEND primitives and their distances from the camera of the last
  // computeModels, for a scene to sort with those of other models.
  std::vector<BlendPrimitive> blendPrimitives() const;
  Status drawBlend(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
                   const std::function<void(const gl::Program&)>& setUniforms, const BlendPrimitive& primitive);
  // The same with lit.frag's lighting uniforms (the viewer).
  Status draw(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
              const Lighting& lighting);

  std::span<const glm::mat4> models() const { return models_; }
  // The morph weights of the last evaluate(), in the asset's MorphLayout order.
  std::span<const float> morphWeights() const { return morphWeights_; }
  const CharacterAsset& asset() const { return *asset_; }

 private:
  Status uploadPalettes(SkinMode mode);
  void uploadMorphWeights();
  Result<ModelFrame> frame(const glm::mat4& viewProjection, SkinMode mode,
                   const std::function<void(const gl::Program&)>& setUniforms);

  std::shared_ptr<const CharacterAsset> asset_;
  Player player_;
  int clip_ = -1;
  std::vector<Srt> locals_;
  std::vector<glm::mat4> models_;      // per runtime joint, camera-relative
  std::vector<glm::mat4> nodeWorlds_;  // per glTF node, camera-relative
  std::vector<glm::mat4> palette_;     // scratch, reused every frame
  std::vector<DualQuat> dualQuats_;    // scratch
  std::vector<gl::Buffer> skinBuffers_;
  std::vector<float> morphWeights_;  // every morphing node's, MorphLayout order
  gl::Buffer morphBuffer_;           // the same on the GPU
  bool palettesCurrent_ = false;  // palettes and weights uploaded since the last pose
  SkinMode uploadedMode_ = SkinMode::Linear;
};

}  // namespace engine
