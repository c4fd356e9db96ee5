#pragma once
// glTF models on the GPU: vertex buffers per primitive, textures per image, and
// the shader variants the model needs. A static mesh is drawn without skinning
// code; a skinned one with 4 or 8 influences, linear blend or dual quaternions,
// each variant built only when first drawn.
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/model_data.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/lighting.h"

namespace engine {

// None draws skinned meshes in their bind pose with the static shader.
enum class SkinMode { Linear, DualQuat, None };

struct ShaderVariant {
  int influences = 0;  // 0 = static, 4 or 8
  SkinMode mode = SkinMode::Linear;
  bool textured = false;   // samples a base colour texture
  bool depthOnly = false;  // shadow passes
  auto operator<=>(const ShaderVariant&) const = default;
  std::string describe() const;
};

// Builds and caches the programs of one vertex + fragment shader pair by variant
// (model.vert + lit.frag for the viewer, scene.vert + scene.frag for scenes), each
// only when first asked for.
class ShaderVariants {
 public:
  explicit ShaderVariants(std::string shaderDir, std::string vertexShader = "model.vert",
                          std::string fragmentShader = "lit.frag", std::vector<std::string> defines = {})
      : shaderDir_(std::move(shaderDir)),
        vertexShader_(std::move(vertexShader)),
        fragmentShader_(std::move(fragmentShader)),
        defines_(std::move(defines)) {}
  // `feedback` names varyings to capture with transform feedback (tests).
  Result<const gl::Program*> get(const ShaderVariant& variant,
                                 const std::vector<std::string>& feedback = {});
  std::vector<ShaderVariant> built() const;

 private:
  std::string shaderDir_;
  std::string vertexShader_;
  std::string fragmentShader_;
  std::vector<std::string> defines_;  // for every variant (shading model, shadows, fog)
  std::map<ShaderVariant, gl::Program> programs_;
};

struct GpuPrimitive {
  gl::VertexArray vao;
  std::vector<gl::Buffer> buffers;
  GLsizei vertexCount = 0;
  GLsizei indexCount = 0;  // 0: not indexed
  int influences = 0;
  int material = -1;
};

class GpuModel {
 public:
  // Uploads every mesh and image of `model`.
  static Result<GpuModel> upload(const ModelData& model);

  const std::vector<std::vector<GpuPrimitive>>& meshes() const { return meshes_; }
  // The base colour texture of a material, or a white one.
  const gl::Texture& baseColor(int material) const;

 private:
  std::vector<std::vector<GpuPrimitive>> meshes_;
  std::vector<gl::Texture> images_;
  std::vector<int> materialImage_;
  gl::Texture white_;
};

// One frame's inputs for drawing a model.
struct ModelFrame {
  glm::mat4 viewProjection{1.0f};
  glm::dvec3 cameraPosition{0.0};
  // World matrix of every glTF node (node order).
  std::span<const glm::mat4> nodeWorlds;
  // One storage buffer per skin: mat4 palette (Linear) or 2 vec4 per joint (DualQuat).
  std::span<const gl::Buffer> skinBuffers;
  SkinMode skinMode = SkinMode::Linear;
  // Sets what the program needs besides the mesh and material (lights, shadows).
  std::function<void(const gl::Program&)> setUniforms;
  bool depthOnly = false;  // shadow passes: no material, depth-only variant
};

// Draws every (node, primitive) instance of the model.
Status drawModel(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                 const ModelFrame& frame);

}  // namespace engine
