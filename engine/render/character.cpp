#include "render/character.h"

#include <algorithm>

#include "anim/jobs.h"

namespace engine {

Result<std::shared_ptr<const CharacterAsset>> CharacterAsset::create(std::shared_ptr<const ModelAsset> source,
                                                                     bool levelsOfDetail) {
  ModelAsset::LevelsOfDetail levels;
  if (levelsOfDetail) {
    auto made = source->levelsOfDetail();
    if (!made) return made.error();
    levels = std::move(made).value();
  }
  auto gpu = GpuModel::upload(source->model, UploadOptions{levelsOfDetail ? &levels : nullptr, &source->materials});
  if (!gpu) return gpu.error();
  const ModelAsset& m = *source;
  return std::shared_ptr<const CharacterAsset>(
      std::make_shared<CharacterAsset>(CharacterAsset{std::move(source), m.model, m.animated, std::move(gpu).value()}));
}

Result<std::shared_ptr<const CharacterAsset>> CharacterAsset::create(ModelData model) {
  auto source = ModelAsset::create(std::move(model));
  if (!source) return source.error();
  return create(std::move(source).value());
}

CharacterInstance::CharacterInstance(std::shared_ptr<const CharacterAsset> asset)
    : asset_(std::move(asset)),
      player_(asset_->animated.skeleton, asset_->animated.morphs.restWeights),
      pose_{{}, asset_->animated.morphs.restWeights} {
  const size_t joints = size_t(asset_->animated.skeleton.jointCount());
  locals_.resize(joints);
  pose_.joints.resize(joints);
  nodeWorlds_.resize(asset_->model.nodes.size());
  for (const Skin& skin : asset_->animated.skins) {
    // Room for either layout: three vec4 (LBS) or two (DQS) per joint.
    skinBuffers_.push_back(gl::Buffer::create(std::max<size_t>(1, skin.joints.size()) * 3 * sizeof(glm::vec4)));
    skinPalettes_.push_back(gl::Texture::ofBuffer(skinBuffers_.back(), GL_RGBA32F));
  }
  if (!pose_.morphWeights.empty()) morphBuffer_ = gl::Buffer::create(pose_.morphWeights.size() * sizeof(float));
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

Status CharacterInstance::evaluate(bool bindPose) {
  palettesCurrent_ = false;
  return playerPose(*asset_->source, player_, bindPose || clip_ < 0, locals_, pose_);
}

void CharacterInstance::setPose(const Pose& pose) {
  std::copy_n(pose.joints.begin(), std::min(pose.joints.size(), pose_.joints.size()), pose_.joints.begin());
  std::copy_n(pose.morphWeights.begin(), std::min(pose.morphWeights.size(), pose_.morphWeights.size()),
              pose_.morphWeights.begin());
  palettesCurrent_ = false;
}

void CharacterInstance::place(const glm::dmat4& world, const glm::dvec3& cameraPosition) {
  root_ = world;
  root_[3] -= glm::dvec4(cameraPosition, 0.0);
  const Skeleton& skeleton = asset_->animated.skeleton;
  for (size_t n = 0; n < nodeWorlds_.size(); ++n)
    nodeWorlds_[n] = glm::mat4(root_ * glm::dmat4(pose_.joints[size_t(skeleton.jointOfRaw(int(n)))]));
}

std::vector<glm::mat4> CharacterInstance::placedJoints() const {
  std::vector<glm::mat4> out;
  for (const glm::mat4& joint : pose_.joints) out.push_back(glm::mat4(root_ * glm::dmat4(joint)));
  return out;
}

Status CharacterInstance::uploadPalettes(SkinMode mode) {
  const auto& skins = asset_->animated.skins;
  for (size_t s = 0; s < skins.size(); ++s) {
    const std::string where = asset_->model.path + ": skin " + std::to_string(s);
    palette_.resize(skins[s].joints.size());
    if (auto status = runJob(SkinningPaletteJob{pose_.joints, skins[s].joints, skins[s].inverseBinds, palette_}, where);
        !status) {
      return status;
    }
    if (mode == SkinMode::DualQuat) {
      dualQuats_.resize(palette_.size());
      if (auto status = runJob(DualQuatPaletteJob{palette_, dualQuats_}, where); !status) return status;
      skinBuffers_[s].upload(0, dualQuats_.size() * sizeof(DualQuat), dualQuats_.data());
    } else {
      lbsPaletteRows(palette_, paletteRows_);
      skinBuffers_[s].upload(0, paletteRows_.size() * sizeof(glm::vec4), paletteRows_.data());
    }
  }
  return Ok{};
}

void CharacterInstance::uploadMorphWeights() {
  if (!pose_.morphWeights.empty()) morphBuffer_.upload(0, pose_.morphWeights.size() * sizeof(float), pose_.morphWeights.data());
}

void CharacterInstance::useSkinCache(SkinPrograms* programs) {
  skinPrograms_ = programs;
  if (programs && !cache_) cache_ = SkinCache::create(asset_->model, asset_->gpu);
  if (!programs) cache_.reset();
  palettesCurrent_ = false;
}

// Shadow passes and probes draw the same pose: upload (and deform) once per pose.
Status CharacterInstance::prepare(SkinMode mode) {
  if (palettesCurrent_ && uploadedMode_ == mode) return Ok{};
  if (auto s = uploadPalettes(mode); !s) return s;
  uploadMorphWeights();
  if (cache_) {
    const SkinCache::Inputs inputs{skinPalettes_, mode, pose_.morphWeights.empty() ? nullptr : &morphBuffer_,
                                   asset_->animated.morphs.first};
    if (auto s = cache_->update(*skinPrograms_, asset_->model, asset_->gpu, inputs); !s) return s;
  }
  palettesCurrent_ = true;
  uploadedMode_ = mode;
  return Ok{};
}

Result<ModelFrame> CharacterInstance::frame(SkinMode mode,
                                           const std::function<void(const gl::Program&)>& setUniforms) {
  if (auto s = prepare(mode); !s) return s.error();
  ModelFrame frame;
  frame.cameraPosition = glm::dvec3(0.0);  // the root is camera-relative already
  frame.root = root_;
  frame.nodeWorlds = nodeWorlds_;
  frame.skinPalettes = skinPalettes_;
  frame.skinMode = mode;
  frame.morphWeights = pose_.morphWeights.empty() ? nullptr : &morphBuffer_;
  frame.morphFirst = asset_->animated.morphs.first;
  frame.skinCache = skinCache();
  frame.setUniforms = setUniforms;
  frame.lodBudget = lodBudget_;
  return frame;
}

Status CharacterInstance::draw(ShaderVariants& variants, SkinMode mode,
                               const std::function<void(const gl::Program&)>& setUniforms, bool depthOnly,
                               bool includeBlend) {
  auto f = frame(mode, setUniforms);
  if (!f) return f.error();
  f->depthOnly = depthOnly;
  f->includeBlend = includeBlend;
  return drawModel(variants, asset_->model, asset_->gpu, *f);
}

Status CharacterInstance::drawPrimitive(ShaderVariants& variants, SkinMode mode,
                                        const std::function<void(const gl::Program&)>& setUniforms, int node,
                                        int primitive, const PrimitivePass& pass) {
  auto f = frame(mode, setUniforms);
  if (!f) return f.error();
  f->depthOnly = pass.depthOnly;
  f->nearSunOnly = pass.nearSunOnly;
  f->surface = pass.surface;
  f->indirect = pass.indirect;
  return drawModelPrimitive(variants, asset_->model, asset_->gpu, *f, node, primitive);
}

std::vector<glm::mat4> CharacterInstance::instanceModels(SkinMode mode, int node, int influences) const {
  ModelFrame f;
  f.cameraPosition = glm::dvec3(0.0);  // as frame(): the root is camera-relative already
  f.root = root_;
  f.nodeWorlds = nodeWorlds_;
  f.skinMode = mode;
  return primitiveInstanceModels(asset_->model, f, node, influences);
}

std::vector<BlendPrimitive> CharacterInstance::blendPrimitives() const {
  return engine::blendPrimitives(asset_->model, asset_->gpu, nodeWorlds_);
}

Status CharacterInstance::drawBlend(ShaderVariants& variants, SkinMode mode,
                                    const std::function<void(const gl::Program&)>& setUniforms,
                                    const BlendPrimitive& primitive, std::span<const IndirectDraw> indirect) {
  auto f = frame(mode, setUniforms);
  if (!f) return f.error();
  f->indirect = indirect;
  return drawBlendPrimitive(variants, asset_->model, asset_->gpu, *f, primitive);
}

}  // namespace engine
