// The model renderer's insides, shared by the files that implement it: shader
// variants (model_renderer_variants.cpp), uploads (_upload) and material binding
// (_material); drawing in model_renderer.cpp. Not part of the engine's interface.
#pragma once

#include <array>

#include "render/model_renderer.h"

namespace engine {

// model_renderer_material.cpp
float classicSpecular(const MaterialData* material);
void setMaterialUniforms(const gl::Program& pr, const MaterialData* material);
void setUvTransforms(const gl::Program& pr, const MaterialData& m);
std::array<bool, kTextureSlots> sampledSlots(const ShaderVariant& v, const MaterialData& m);
int layerTextureMask(const MaterialData& m);
void bindMaterialOrWhite(const GpuModel& gpu, const MaterialData* m, const ShaderVariant& v);
void unbindMaterialSamplers(const ShaderVariant& v, const MaterialData& m);
const MaterialData* materialOf(const ModelData& model, int material);

}  // namespace engine
