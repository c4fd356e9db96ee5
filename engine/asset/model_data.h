#pragma once
// The engine's own plain copy of a glTF model: what the loader hands to anim and
// render, so that no other folder sees tinygltf. Everything is validated on load:
// indices are in range, times sorted, weights normalised.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

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
};

struct PrimitiveData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // empty or one per position
  std::vector<glm::vec2> uvs;       // TEXCOORD_0; empty or one per position
  std::vector<glm::vec4> tangents;  // empty or one per position
  std::vector<std::uint32_t> indices;  // empty for non-indexed primitives
  // Skinning: `influences` (0, 4 or 8) entries per vertex in `joints` and
  // `weights`; JOINTS_1/WEIGHTS_1 give the last four. Weights sum to 1.
  int influences = 0;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  int material = -1;
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

struct MeshData {
  std::string name;
  std::vector<PrimitiveData> primitives;
  // Default morph target weights, one per target (every primitive of a mesh has
  // the same number); zeros when the file gives none.
  std::vector<float> morphWeights;
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF 2.0's metallic-roughness material. Image indices are into
// ModelData::images, -1 = none. Only TEXCOORD_0 is read: a texture that asks for
// another set is still sampled with the first (the loader warns).
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

struct ModelData {
  std::string path;
  std::vector<NodeData> nodes;
  std::vector<int> sceneRoots;  // roots of the default scene (all roots if none)
  std::vector<MeshData> meshes;
  std::vector<MaterialData> materials;
  std::vector<ImageData> images;
  std::vector<SkinData> skins;
  std::vector<AnimationData> animations;
  std::vector<std::string> warnings;  // also logged; kept for tests and tools
};

}  // namespace engine
