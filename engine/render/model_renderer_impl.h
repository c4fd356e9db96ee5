// The model renderer's insides, shared by the files that implement it: shader
// variants (model_renderer_variants.cpp), uploads (_upload) and material binding
// (_material); drawing in model_renderer.cpp. Not part of the engine's interface.
#pragma once

#include <array>

#include "render/model_renderer.h"

namespace engine {

// model_renderer_material.cpp
// The uniforms and textures read the scene layer's table (GpuModel::material); the
// variants, made before a draw has one, what the glTF material has.
void setMaterialUniforms(const gl::Program& pr, const SceneMaterial& material);
void setUvTransforms(const gl::Program& pr, const SceneMaterial& m);
// Which slots have an image.
std::array<bool, kTextureSlots> presentSlots(const MaterialData& m);
std::array<bool, kTextureSlots> presentSlots(const SceneMaterial& m);
std::array<bool, kTextureSlots> sampledSlots(const ShaderVariant& v, const std::array<bool, kTextureSlots>& present);
int layerTextureMask(const SceneMaterial& m);
// `m` null: glTF's default material, which shades with a white base colour.
void bindMaterialOrWhite(const GpuModel& gpu, const SceneMaterial* m, const ShaderVariant& v);
void unbindMaterialSamplers(const ShaderVariant& v, const SceneMaterial& m);
const MaterialData* materialOf(const ModelData& model, int material);

}  // namespace engine
