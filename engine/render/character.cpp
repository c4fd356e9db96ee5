#include "render/character.h"

#include <algorithm>

#include "anim/jobs.h"

namespace engine {

Result<std::shared_ptr<const CharacterAsset>> CharacterAsset::create(ModelData model) {
  auto animated = buildAnimatedModel(model);
  if (!animated) return animated.error();
  auto gpu = GpuModel::upload(model);
  if (!gpu) return gpu.error();
  auto asset = std::make_shared<CharacterAsset>(
      CharacterAsset{std::move(model), std::move(animated).value(), std::move(gpu).value()});
  return std::shared_ptr<const CharacterAsset>(std::move(asset));
}

namespace {

// The clip times that the bounds sample: `samples` + 1 evenly spaced, and every
// key of a morph track, where LINEAR weights (and so the vertices) peak.
std::vector<double> boundsSampleTimes(const Clip& clip, int samples) {
  std::vector<double> times;
  for (int i = 0; i <= samples; ++i) times.push_back(clip.duration() * double(i) / double(samples));
  for (const MorphTrack& track : clip.morphTracks()) times.insert(times.end(), track.times.begin(), track.times.end());
  return times;
}

}  // namespace

Result<CharacterAsset::Bounds> CharacterAsset::boundsOfAllPoses(int samples) const {
  Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  const Skeleton& skeleton = animated.skeleton;
  const MorphLayout& morphs = animated.morphs;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  std::vector<float> weights = morphs.restWeights;
  std::vector<glm::mat4> models(locals.size());
  std::vector<glm::vec3> posed;
  auto addPose = [&]() -> Status {
    if (auto s = runJob(LocalToModelJob{skeleton.parents(), locals, glm::mat4(1.0f), models}, model.path); !s) return s;
    for (size_t n = 0; n < model.nodes.size(); ++n) {
      const NodeData& node = model.nodes[n];
      if (node.mesh < 0) continue;
      for (const PrimitiveData& prim : model.meshes[size_t(node.mesh)].primitives) {
        const bool skinned = node.skin >= 0 && prim.influences > 0;
        const PrimitivePose pose{morphs.of(weights, int(n)), skinned ? &animated.skins[size_t(node.skin)] : nullptr,
                                 models, models[size_t(skeleton.jointOfRaw(int(n)))]};
        posed.resize(prim.positions.size());
        if (!posePrimitive(prim, pose, posed)) {
          return makeError(model.path + ": node " + std::to_string(n) + ": morphing or skinning rejected its inputs");
        }
        for (const glm::vec3& p : posed) {
          b.min = glm::min(b.min, p);
          b.max = glm::max(b.max, p);
        }
      }
    }
    return Ok{};
  };
  if (auto s = addPose(); !s) return s.error();
  for (const Clip& clip : animated.clips) {
    for (const double time : boundsSampleTimes(clip, samples)) {
      const std::string where = model.path + ": clip " + clip.name();
      if (auto s = runJob(SamplingJob{&clip, time, skeleton.restPose(), locals}, where); !s) return s.error();
      if (auto s = runJob(MorphSamplingJob{&clip, time, morphs.restWeights, weights}, where); !s) return s.error();
      if (auto s = addPose(); !s) return s.error();
    }
  }
  if (b.min.x > b.max.x) b = Bounds{};
  return b;
}

CharacterInstance::CharacterInstance(std::shared_ptr<const CharacterAsset> asset)
    : asset_(std::move(asset)),
      player_(asset_->animated.skeleton, asset_->animated.morphs.restWeights),
      morphWeights_(asset_->animated.morphs.restWeights) {
  const size_t joints = size_t(asset_->animated.skeleton.jointCount());
  locals_.resize(joints);
  models_.resize(joints);
  nodeWorlds_.resize(asset_->model.nodes.size());
  for (const Skin& skin : asset_->animated.skins) {
    // Room for either layout: one mat4 (LBS) or two vec4 (DQS) per joint.
    skinBuffers_.push_back(gl::Buffer::create(std::max<size_t>(1, skin.joints.size()) * sizeof(glm::mat4)));
  }
  if (!morphWeights_.empty()) morphBuffer_ = gl::Buffer::create(morphWeights_.size() * sizeof(float));
}

void CharacterInstance::play(int clip, LoopMode mode, double start) {
  clip_ = clip;
  if (clip < 0 || clip >= int(asset_->animated.clips.size())) return;
  player_.play(asset_->animated.clips[size_t(clip)], mode);
  player_.seek(start);
}

void CharacterInstance::crossFade(int clip, double seconds) {
  if (clip < 0 || clip >= int(asset_->animated.clips.size()) || !player_.clip()) {
    play(clip);
    return;
  }
  clip_ = clip;
  player_.crossFade(asset_->animated.clips[size_t(clip)], seconds);
}

void CharacterInstance::evaluate(bool bindPose) {
  const auto rest = asset_->animated.skeleton.restPose();
  const auto restWeights = std::span<const float>(asset_->animated.morphs.restWeights);
  if (bindPose || clip_ < 0 || !player_.evaluate(locals_, morphWeights_)) {
    std::copy(rest.begin(), rest.end(), locals_.begin());
    std::copy(restWeights.begin(), restWeights.end(), morphWeights_.begin());
  }
  palettesCurrent_ = false;
}

Status CharacterInstance::computeModels(const glm::dmat4& transform, const glm::dvec3& cameraPosition) {
  glm::dmat4 root = transform;
  root[3] -= glm::dvec4(cameraPosition, 0.0);
  const Skeleton& skeleton = asset_->animated.skeleton;
  palettesCurrent_ = false;
  if (auto s = runJob(LocalToModelJob{skeleton.parents(), locals_, glm::mat4(root), models_}, asset_->model.path);
      !s) {
    return s;
  }
  for (size_t n = 0; n < nodeWorlds_.size(); ++n) nodeWorlds_[n] = models_[size_t(skeleton.jointOfRaw(int(n)))];
  return Ok{};
}

Status CharacterInstance::uploadPalettes(SkinMode mode) {
  const auto& skins = asset_->animated.skins;
  for (size_t s = 0; s < skins.size(); ++s) {
    const std::string where = asset_->model.path + ": skin " + std::to_string(s);
    palette_.resize(skins[s].joints.size());
    if (auto status = runJob(SkinningPaletteJob{models_, skins[s].joints, skins[s].inverseBinds, palette_}, where);
        !status) {
      return status;
    }
    if (mode == SkinMode::DualQuat) {
      dualQuats_.resize(palette_.size());
      if (auto status = runJob(DualQuatPaletteJob{palette_, dualQuats_}, where); !status) return status;
      skinBuffers_[s].upload(0, dualQuats_.size() * sizeof(DualQuat), dualQuats_.data());
    } else {
      skinBuffers_[s].upload(0, palette_.size() * sizeof(glm::mat4), palette_.data());
    }
  }
  return Ok{};
}

void CharacterInstance::uploadMorphWeights() {
  if (!morphWeights_.empty()) morphBuffer_.upload(0, morphWeights_.size() * sizeof(float), morphWeights_.data());
}

Result<ModelFrame> CharacterInstance::frame(const glm::mat4& viewProjection, SkinMode mode,
                                           const std::function<void(const gl::Program&)>& setUniforms) {
  // Shadow passes draw the same pose: upload the palettes once per pose.
  if (!palettesCurrent_ || uploadedMode_ != mode) {
    if (auto s = uploadPalettes(mode); !s) return s.error();
    uploadMorphWeights();
    palettesCurrent_ = true;
    uploadedMode_ = mode;
  }
  ModelFrame frame;
  frame.viewProjection = viewProjection;
  frame.cameraPosition = glm::dvec3(0.0);  // the models are camera-relative already
  frame.nodeWorlds = nodeWorlds_;
  frame.skinBuffers = skinBuffers_;
  frame.skinMode = mode;
  frame.morphWeights = morphWeights_.empty() ? nullptr : &morphBuffer_;
  frame.morphFirst = asset_->animated.morphs.first;
  frame.setUniforms = setUniforms;
  return frame;
}

Status CharacterInstance::draw(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
                               const std::function<void(const gl::Program&)>& setUniforms, bool depthOnly,
                               bool includeBlend) {
  auto f = frame(viewProjection, mode, setUniforms);
  if (!f) return f.error();
  f->depthOnly = depthOnly;
  f->includeBlend = includeBlend;
  return drawModel(variants, asset_->model, asset_->gpu, *f);
}

std::vector<BlendPrimitive> CharacterInstance::blendPrimitives() const {
  return engine::blendPrimitives(asset_->model, asset_->gpu, nodeWorlds_);
}

Status CharacterInstance::drawBlend(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
                                    const std::function<void(const gl::Program&)>& setUniforms,
                                    const BlendPrimitive& primitive) {
  auto f = frame(viewProjection, mode, setUniforms);
  if (!f) return f.error();
  return drawBlendPrimitive(variants, asset_->model, asset_->gpu, *f, primitive);
}

Status CharacterInstance::draw(ShaderVariants& variants, const glm::mat4& viewProjection, SkinMode mode,
                               const Lighting& lighting) {
  return draw(variants, viewProjection, mode,
              [&lighting](const gl::Program& program) { setLightingUniforms(program, lighting); });
}

}  // namespace engine
