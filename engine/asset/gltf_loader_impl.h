// The glTF loader's insides, shared by the files that implement it: the checks of
// the input (gltf_loader_guard.cpp), images (_images), materials and their
// extensions (_materials), meshes (_meshes), the node tree with skins, cameras,
// lights and instancing (_nodes) and animation (_animation); parsing and the
// public face in gltf_loader.cpp. Not part of the engine's interface.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "asset/gltf_accessor.h"
#include "asset/gltf_loader.h"
#include "asset/model_data.h"
#include "core/result.h"

namespace engine::gltf_loader {

using gltf::AccessorValues;
using gltf::readAccessor;

inline constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
inline constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"

inline std::string str(std::size_t i) { return std::to_string(i); }
inline std::string str(int i) { return std::to_string(i); }

// How errors name an element: its kind and index, and its name when it has one
// ("material 2 (\"paint\")").
inline std::string labelled(const char* kind, std::size_t index, const std::string& name) {
  return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " (\"" + name + "\")");
}

inline bool validIndex(int index, std::size_t size) {
  return index >= 0 && static_cast<std::size_t>(index) < size;
}

inline std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;  // GLB is little-endian, as is every platform we build for
}

inline std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// gltf_loader_guard.cpp: the file and its raw JSON, before tinygltf sees them.
Result<std::vector<unsigned char>> readFileBytes(const std::string& path);
Result<std::string> glbJson(const std::vector<unsigned char>& bytes, const std::string& path);
std::vector<unsigned char> withGlbJson(const std::vector<unsigned char>& bytes, std::string json);
Status checkRawJson(const std::string& jsonText, const std::string& path, std::vector<std::string>& warnings);
bool guardedReadWholeFile(std::vector<unsigned char>* out, std::string* err,
                          const std::string& filepath, void* userData);

// gltf_loader_images.cpp: tinygltf's image loader and the decoding after it.
bool tolerantImageLoader(tinygltf::Image* image, const int imageIndex, std::string* err,
                         std::string* warn, int reqWidth, int reqHeight,
                         const unsigned char* bytes, int size, void*);
void decodeImages(tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings);

// tinygltf's model into ModelData, one step after the other (run, in
// gltf_loader.cpp); each step lives in the file of its concern.
class Converter {
 public:
  Converter(const tinygltf::Model& gltf, ModelData& out, int scene) : gltf_(gltf), out_(out), file_(out.path), scene_(scene) {}

  Status run();

 private:
  Error error(const std::string& message) const { return makeError(file_ + ": " + message); }
  void warn(const std::string& message) { out_.warnings.push_back(file_ + ": " + message); }

  // gltf_loader_guard.cpp
  Status checkLimits();

  // gltf_loader_nodes.cpp
  Status convertNodes();
  Status convertNode(std::size_t i);
  Status readNodeTransform(const tinygltf::Node& src, NodeData& node, const std::string& name);
  Status checkTree();
  Status findSceneRoots();
  void leaveOutOtherScenes();
  Status resolveNodeWeights();
  Status convertSkins();
  Status checkSkinnedMeshes();
  Status convertCameras();
  Result<CameraData> convertCamera(const tinygltf::Camera& src, const std::string& where);
  Status convertLights();
  Result<PunctualLightData> convertLight(const tinygltf::Light& src, const std::string& where);
  Status convertInstancing();
  Result<std::optional<AccessorValues>> instancingAttribute(const tinygltf::Value& attributes, const char* semantic,
                                                            int components, const std::string& where) const;
  Status readInstancing(const tinygltf::Value& ext, std::size_t n);
  static glm::mat4 instanceMatrix(const std::optional<AccessorValues> (&parts)[3], std::size_t i);

  // gltf_loader_images.cpp
  Status convertImages();
  static bool toRgba8(const tinygltf::Image& src, Image& dst);

  // gltf_loader_materials.cpp
  template <typename Info>
  int textureImage(const Info& info, const std::string& material, const char* slotName, TextureSlotData& slot);
  struct ExtensionTextureInfo;
  static ExtensionTextureInfo extensionTextureInfo(const tinygltf::Value& v);
  void readLayerTextures(const tinygltf::Material& src, const std::string& name, MaterialData& m);
  static float normalScale(const tinygltf::Value& info);
  void readTextureTransform(const tinygltf::Value& ext, const std::string& where, TextureSlotData& slot,
                            int& texCoord);
  SamplerData readSampler(int index, const std::string& where);
  std::string imageName(int image) const;
  Status convertMaterials();

  // gltf_loader_meshes.cpp
  void addMissingTangents(PrimitiveData& prim, const std::string& name);
  void checkUvSets(PrimitiveData& prim, const std::string& name);
  Result<std::vector<float>> readFloats(int accessor, int components, std::size_t count,
                                        const std::string& context);
  template <typename Vec>
  static std::vector<Vec> toVectors(const std::vector<float>& flat);
  Status convertMeshes();
  static int targetCount(const MeshData& mesh);
  Status readMeshWeights(const tinygltf::Mesh& src, MeshData& mesh, const std::string& name);
  Status convertVariants();
  Result<std::vector<float>> readWeightList(const std::vector<double>& src, int targets, const std::string& name) const;
  static int attribute(const tinygltf::Primitive& src, const char* name);
  Status convertPrimitive(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name);
  Status readVertexColors(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name);
  Status readMorphTargets(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name);
  static std::vector<glm::vec3>* morphDeltas(PrimitiveData& prim, const std::string& attribute);
  Status readIndices(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name);
  Status readSkinAttributes(const tinygltf::Primitive& src, PrimitiveData& prim, const std::string& name);
  static void normaliseWeights(PrimitiveData& prim);

  // gltf_loader_animation.cpp
  Status convertAnimations();
  Status convertChannel(const tinygltf::Animation& src, std::size_t c, AnimationData& anim, const std::string& name);
  Status readKeys(const tinygltf::AnimationSampler& sampler, const std::string& name, Interpolation& interpolation,
                  std::vector<float>& times);
  Status convertMorphChannel(const tinygltf::AnimationChannel& ch, const tinygltf::AnimationSampler& sampler,
                             MorphChannelData& channel, const std::string& name, const std::string& samplerName);
  Result<std::vector<float>> readTimes(int accessor, const std::string& name);
  Status readValues(int accessor, ChannelData& channel, const std::string& name);

  const tinygltf::Model& gltf_;
  ModelData& out_;
  std::string file_;
  int scene_ = -1;  // the scene asked for; -1 the file's default
};

}  // namespace engine::gltf_loader
