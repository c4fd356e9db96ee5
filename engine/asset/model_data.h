#pragma once
// The engine's own plain copy of a glTF model: what the loader hands to anim and
// render, so that no other folder sees tinygltf. Everything is validated on load:
// indices are in range, times sorted, weights normalised.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/material_layers.h"
#include "core/image.h"
#include "core/keyframe.h"

namespace engine {

struct NodeData {
  std::string name;
  int parent = -1;  // -1 for a root
  std::vector<int> children;
  // Local transform; a glTF `matrix` is decomposed into these on load.
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order w, x, y, z; normalised
  glm::vec3 scale{1.0f};
  int mesh = -1;
  int skin = -1;
  // Default morph target weights of this instance of `mesh`: the node's own
  // `weights` when the file gives them (glTF: they override the mesh's), else a
  // copy of MeshData::morphWeights; one per target, empty without targets.
  std::vector<float> morphWeights;
  // EXT_mesh_gpu_instancing: the local transform (TRS) of each instance of `mesh`,
  // applied after the node's world matrix (instance world = node world * this).
  // Empty without the extension: the mesh is drawn once, at the node. Always empty
  // on a skinned node (the loader warns and drops it: a skin places its vertices
  // by its joints, so the node's instance transforms would have nothing to move).
  std::vector<glm::mat4> instances;
  // KHR_lights_punctual: the index into ModelData::lights this node places, -1 none.
  int light = -1;
  // The index into ModelData::cameras this node places (looking along its -Z, up
  // its +Y), -1 none.
  int camera = -1;
};

// The local transforms `node`'s mesh is drawn with: its instances, or one identity
// when it has none, so that every consumer loops the same way.
inline std::span<const glm::mat4> meshInstances(const NodeData& node) {
  static const glm::mat4 kOne{1.0f};
  if (node.instances.empty()) return {&kOne, 1};
  return node.instances;
}

struct PrimitiveData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // empty or one per position
  std::vector<glm::vec2> uvs;       // TEXCOORD_0; empty or one per position
  // TEXCOORD_1; empty or one per position. When a material texture asks for set 1
  // and the mesh has none, the loader warns and copies set 0 here.
  std::vector<glm::vec2> uvs1;
  // COLOR_0, linear RGBA (RGB files get alpha 1); empty or one per position. It
  // multiplies the base colour (alpha too, where the material is MASK or BLEND).
  std::vector<glm::vec4> colors;
  std::vector<glm::vec4> tangents;  // empty or one per position
  std::vector<std::uint32_t> indices;  // empty for non-indexed primitives
  // Skinning: `influences` (0, 4 or 8) entries per vertex in `joints` and
  // `weights`; JOINTS_1/WEIGHTS_1 give the last four. Weights sum to 1.
  int influences = 0;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  int material = -1;
  // KHR_materials_variants: the material of each of ModelData::variants, -1 where
  // the variant keeps `material` (asset/material_variants.h); empty without them.
  std::vector<int> variantMaterials;
  int mode = 4;  // glTF primitive mode, 4 = triangles
  // Morph targets: `morphTargets` sets of displacements, target-major (target t
  // moves vertex v by [t * vertices + v]), so a target's deltas are one span.
  // Each array is empty when no target moves that attribute, and zero for the
  // targets that do not. Tangent deltas move xyz; the handedness w is kept.
  int morphTargets = 0;
  std::vector<glm::vec3> morphPositions;
  std::vector<glm::vec3> morphNormals;
  std::vector<glm::vec3> morphTangents;
};

// Whether `p` is a triangle list drawn by index (glTF mode 4 with whole triangles).
inline bool isIndexedTriangleList(const PrimitiveData& p) {
  return p.mode == 4 && !p.indices.empty() && p.indices.size() % 3 == 0;
}

struct MeshData {
  std::string name;
  std::vector<PrimitiveData> primitives;
  // Default morph target weights, one per target (every primitive of a mesh has
  // the same number); zeros when the file gives none.
  std::vector<float> morphWeights;
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF sampler settings, with glTF's (= GL's) enum values.
enum class TextureWrap { Repeat = 10497, ClampToEdge = 33071, MirroredRepeat = 33648 };
enum class TextureFilter {
  Nearest = 9728,
  Linear = 9729,
  NearestMipmapNearest = 9984,
  LinearMipmapNearest = 9985,
  NearestMipmapLinear = 9986,
  LinearMipmapLinear = 9987,
};

// A texture without a sampler (glTF: "repeat wrapping and auto filtering") gets
// these: trilinear, as every texture of the engine was before samplers were read.
struct SamplerData {
  TextureWrap wrapS = TextureWrap::Repeat;
  TextureWrap wrapT = TextureWrap::Repeat;
  TextureFilter magFilter = TextureFilter::Linear;
  TextureFilter minFilter = TextureFilter::LinearMipmapLinear;
  auto operator<=>(const SamplerData&) const = default;
};

// The material texture slots, in the order of MaterialData::textures.
// The last twelve are glTF's dielectric layers' (asset/material_layers.h):
// KHR_materials_specular's specularTexture (A) and specularColorTexture (RGB, sRGB),
// KHR_materials_clearcoat's clearcoatTexture (R) and clearcoatRoughnessTexture (G),
// KHR_materials_transmission's transmissionTexture (R), KHR_materials_volume's
// thicknessTexture (G), the coat's own normal map (clearcoatNormalTexture), and
// KHR_materials_sheen's sheenColorTexture (RGB, sRGB) and sheenRoughnessTexture (A),
// KHR_materials_anisotropy's anisotropyTexture (RG direction, B strength),
// KHR_materials_iridescence's iridescenceTexture (R) and
// iridescenceThicknessTexture (G).
enum class TextureSlot {
  BaseColor,
  Normal,
  MetallicRoughness,
  Emissive,
  Occlusion,
  Specular,
  SpecularColor,
  Clearcoat,
  ClearcoatRoughness,
  Transmission,
  Thickness,
  ClearcoatNormal,
  SheenColor,
  SheenRoughness,
  Anisotropy,
  Iridescence,
  IridescenceThickness
};
inline constexpr int kTextureSlots = 17;
inline constexpr int kFirstLayerSlot = 5;  // Specular
// Colour slots hold sRGB-encoded images; the others linear data.
inline bool isSrgbSlot(TextureSlot slot) {
  return slot == TextureSlot::BaseColor || slot == TextureSlot::Emissive || slot == TextureSlot::SpecularColor ||
         slot == TextureSlot::SheenColor;
}
// The slot's key in glTF ("baseColorTexture", ..., "iridescenceThicknessTexture"),
// for messages and the viewer's material panel.
inline const char* textureSlotName(TextureSlot slot) {
  static constexpr const char* kNames[] = {
      "baseColorTexture",          "normalTexture",       "metallicRoughnessTexture", "emissiveTexture",
      "occlusionTexture",          "specularTexture",     "specularColorTexture",     "clearcoatTexture",
      "clearcoatRoughnessTexture", "transmissionTexture", "thicknessTexture",         "clearcoatNormalTexture",
      "sheenColorTexture",         "sheenRoughnessTexture", "anisotropyTexture",      "iridescenceTexture",
      "iridescenceThicknessTexture"};
  static_assert(std::size(kNames) == kTextureSlots);
  return kNames[static_cast<int>(slot)];
}

// How one slot reads its texture: which uv set, KHR_texture_transform's matrix
// (asset/texture_transform.h; identity without the extension) and the sampler.
struct TextureSlotData {
  int texCoord = 0;  // 0 or 1 (others are warned about and read as 0)
  glm::mat3 uvTransform{1.0f};
  SamplerData sampler;
  // Whether the slot needs more than TEXCOORD_0 as it is (a set other than 0 or a
  // transform): only then does a draw pay for the uv transform.
  bool transformsUv() const { return texCoord != 0 || uvTransform != glm::mat3(1.0f); }
};

// glTF 2.0's metallic-roughness material. Image indices are into
// ModelData::images, -1 = none; `textures` says how each slot samples its image.
struct MaterialData {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  int baseColorImage = -1;  // sRGB
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  int metallicRoughnessImage = -1;  // linear: G = roughness, B = metallic
  int normalImage = -1;             // linear, tangent space, +Y up (OpenGL convention)
  float normalScale = 1.0f;         // scales the map's X and Y
  int occlusionImage = -1;          // linear, R; darkens the ambient term only
  float occlusionStrength = 1.0f;
  int emissiveImage = -1;  // sRGB
  glm::vec3 emissiveFactor{0.0f};
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // MASK: fragments with alpha below it are discarded
  bool doubleSided = false;  // no back-face culling; back faces flip the normal
  // KHR_materials_unlit: the surface shows its base colour (factor x texture x
  // vertex colour) as it is, lit by nothing; every renderer draws it so.
  bool unlit = false;
  // KHR_materials_ior, _specular, _clearcoat, _transmission, _volume, _sheen, _anisotropy, _iridescence: the factors, and their textures'
  // images (-1 none; the slots past Occlusion).
  MaterialLayers layers;
  std::array<int, kTextureSlots - kFirstLayerSlot> layerImages{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  bool hasLayerTextures() const {
    for (int image : layerImages)
      if (image >= 0) return true;
    return false;
  }
  // Whether the layered BRDF is needed at all (else plain metallic-roughness).
  bool layered() const { return !layers.isDefault() || hasLayerTextures(); }
  std::array<TextureSlotData, kTextureSlots> textures;  // by TextureSlot
  const TextureSlotData& texture(TextureSlot slot) const { return textures[static_cast<std::size_t>(slot)]; }
  TextureSlotData& texture(TextureSlot slot) { return textures[static_cast<std::size_t>(slot)]; }
  // The image of `slot` (the *Image fields above), -1 = none.
  int image(TextureSlot slot) const {
    switch (slot) {
      case TextureSlot::BaseColor: return baseColorImage;
      case TextureSlot::Normal: return normalImage;
      case TextureSlot::MetallicRoughness: return metallicRoughnessImage;
      case TextureSlot::Emissive: return emissiveImage;
      case TextureSlot::Occlusion: return occlusionImage;
      case TextureSlot::Specular:
      case TextureSlot::SpecularColor:
      case TextureSlot::Clearcoat:
      case TextureSlot::ClearcoatRoughness:
      case TextureSlot::Transmission:
      case TextureSlot::Thickness:
      case TextureSlot::ClearcoatNormal:
      case TextureSlot::SheenColor:
      case TextureSlot::SheenRoughness:
      case TextureSlot::Anisotropy:
      case TextureSlot::Iridescence:
      case TextureSlot::IridescenceThickness: return layerImages[std::size_t(slot) - kFirstLayerSlot];
    }
    return -1;
  }
};

struct ImageData {
  std::string name;
  std::string uri;       // empty for embedded images
  bool missing = false;  // could not be read or decoded: `image` is a 1x1 white fallback
  Image image;           // RGBA8
};

struct SkinData {
  std::string name;
  std::vector<int> joints;              // node indices
  std::vector<glm::mat4> inverseBinds;  // one per joint (identity when absent)
  int skeleton = -1;                    // node index, informational
};

struct ChannelData {
  int node = -1;
  AnimPath path = AnimPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // >= 0, non-decreasing, finite
  // One value per key (three for CUBICSPLINE: in-tangent, value, out-tangent).
  // Translation and scale use xyz; rotation is glTF order x, y, z, w.
  std::vector<glm::vec4> values;
};

// A `weights` channel: the morph target weights of one node's mesh.
struct MorphChannelData {
  int node = -1;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // as ChannelData::times
  int targets = 0;           // weights per key: the mesh's target count
  // `targets` weights per key; for CUBICSPLINE three blocks of `targets` per key
  // (in-tangents, values, out-tangents), as glTF stores them.
  std::vector<float> values;
};

struct AnimationData {
  std::string name;
  std::vector<ChannelData> channels;
  std::vector<MorphChannelData> morphChannels;
  float duration = 0.0f;  // largest last key time of any channel
};

// A glTF camera. Perspective: yfov (radians), znear, zfar (0: infinite) and the
// aspect ratio it was made for (0: none; the viewer keeps its frame's). Orthographic:
// xmag, ymag and both planes.
struct CameraData {
  std::string name;
  bool perspective = true;
  float yfov = 0.8f;
  float aspectRatio = 0.0f;
  float znear = 0.1f, zfar = 0.0f;
  float xmag = 1.0f, ymag = 1.0f;
};

// A KHR_lights_punctual light, as the file gives it; its node places it (at the
// node's origin, shining along the node's -Z), a spot light with its cones
// (asset/model_lights.h makes them scene lights).
enum class PunctualType { Directional, Point, Spot };
struct PunctualLightData {
  std::string name;
  PunctualType type = PunctualType::Point;
  glm::vec3 color{1.0f};   // linear RGB
  float intensity = 1.0f;  // directional: lux (lm/m^2); point and spot: candela (lm/sr)
  float range = 0.0f;      // 0: infinite (the engine's lights always are)
  float innerConeAngle = 0.0f, outerConeAngle = 0.7853982f;  // spot, radians
};

struct ModelData {
  std::string path;
  std::vector<NodeData> nodes;
  std::vector<int> sceneRoots;  // roots of the scene drawn (all roots if none)
  int scene = -1;               // the one drawn (-1: none, every root is drawn)
  std::vector<MeshData> meshes;
  std::vector<MaterialData> materials;
  std::vector<ImageData> images;
  std::vector<SkinData> skins;
  std::vector<AnimationData> animations;
  std::vector<PunctualLightData> lights;  // KHR_lights_punctual
  std::vector<std::string> variants;      // KHR_materials_variants' names
  std::vector<CameraData> cameras;
  std::vector<std::string> warnings;  // also logged; kept for tests and tools
};

// The node that places camera `camera` (its first, as glTF allows several), -1 none.
inline int cameraNode(const ModelData& model, int camera) {
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].camera == camera) return int(n);
  return -1;
}

}  // namespace engine
