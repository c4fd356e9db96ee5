#pragma once
// One material table for both renderers: the scene file's materials and a glTF
// model's (classic weights, metallic-roughness, every KHR layer, alpha, sidedness)
// in engine units, with references to their images, decoded once by the scene layer
// (scene/scene_images.h) or with their model (ModelData::images). The rasterizer's
// uniforms (render/material_uniforms.h) and the tracers' material table
// (raytrace/scene_builder.cpp, RtScene::fromSceneDesc) both read it, so that what
// glTF's metallic-roughness means to the classic model lives here alone. GL-free.
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"
#include "asset/scene_desc.h"
#include "core/image.h"

namespace engine {

struct SceneImages;

// glTF has no classic weights: its highlight is the roughness turned around (none at
// roughness 1), the rest MaterialDesc's defaults (ambient 0.1, diffuse 0.9,
// shininess 32, no mirror), which the classic model was tuned with.
inline float classicSpecularOf(float roughness) { return 0.5f * (1.0f - roughness); }

// Which image row uv v = 0 reads: glTF's images as they are (the top row); the scene
// file's textures are uploaded flipped (the bottom row).
enum class UvOrigin { TopLeft, BottomLeft };

// One texture slot of a material: its image's index among its owner's images (what
// the rasterizer uploads once per image; -1 none), the decoded image itself (owned
// by the table's owner: the model's ModelData::images, or the scene's SceneImages,
// which outlive the table), and how the slot samples it.
struct MaterialTexture {
  int image = -1;
  const Image* decoded = nullptr;
  TextureSlotData sampling;
  bool present() const { return image >= 0; }
};

struct SceneMaterial {
  // The shading weights in engine units: the classic model's, metallic-roughness,
  // emission, every KHR layer and the scene file's texture scale (the `texture`
  // path is not read: the decoded image is textures[BaseColor]).
  MaterialDesc surface;
  // glTF's alpha: the base colour factor's, its mode and MASK's cutoff.
  float alpha = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  // Back faces drawn (and their normal flipped); the tracers let rays through the
  // back of a one-sided material, as the rasterizer culls it.
  bool doubleSided = false;
  bool unlit = false;  // KHR_materials_unlit
  bool blends() const { return alphaMode == AlphaMode::Blend; }
  bool transmissive() const { return surface.layers.transmissive(); }
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  // The layered BRDF is needed (MaterialData::layered): layers away from their
  // defaults, or a layer texture.
  bool layered = false;
  UvOrigin origin = UvOrigin::TopLeft;
  std::array<MaterialTexture, kTextureSlots> textures{};

  glm::vec4 baseColor() const { return glm::vec4(surface.color, alpha); }
  const MaterialTexture& texture(TextureSlot slot) const { return textures[std::size_t(slot)]; }
};

// A glTF material; its textures refer to `model`'s images.
SceneMaterial gltfMaterial(const MaterialData& material, const ModelData& model);
// glTF's default material, for a primitive without one: white, dielectric, fully
// rough, one-sided.
SceneMaterial gltfDefaultMaterial();
// Every material of `model`, in its order.
std::vector<SceneMaterial> gltfMaterials(const ModelData& model);
// The glTF material `material` of `table` (gltfMaterials), or the default one where
// it is -1 or out of range, as the rasterizer has always drawn such primitives.
const SceneMaterial& gltfMaterialOf(std::span<const SceneMaterial> table, int material);

// A scene file's material as the file gives it, with its decoded texture (null
// none; image index `index` among the scene's material textures). Two-sided: the
// tracers never let rays through a scene shape's back.
SceneMaterial sceneFileMaterial(const MaterialDesc& material, const Image* texture, int index);
// Every material of the scene file, their textures in `images`.
std::vector<SceneMaterial> sceneFileMaterials(const SceneDesc& desc, const SceneImages& images);

}  // namespace engine
