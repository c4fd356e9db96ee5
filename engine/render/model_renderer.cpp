#include "render/model_renderer.h"

#include <glm/gtc/matrix_transform.hpp>

namespace engine {

std::string ShaderVariant::describe() const {
  std::string name = influences == 0 ? "static"
                                     : std::string(mode == SkinMode::DualQuat ? "dqs" : "lbs") +
                                           std::to_string(influences);
  if (textured) name += "+textured";
  if (depthOnly) name += "+depth";
  return name;
}

Result<const gl::Program*> ShaderVariants::get(const ShaderVariant& variant,
                                              const std::vector<std::string>& feedback) {
  if (feedback.empty()) {
    if (auto it = programs_.find(variant); it != programs_.end()) return &it->second;
  }
  std::vector<std::string> defines = defines_;
  if (variant.textured) defines.push_back("TEXTURED 1");
  if (variant.depthOnly) defines.push_back("DEPTH_ONLY 1");
  if (variant.influences > 0) {
    defines.push_back("SKINNED 1");
    defines.push_back("INFLUENCES " + std::to_string(variant.influences));
    if (variant.mode == SkinMode::DualQuat) defines.push_back("DUAL_QUAT 1");
  }
  const std::string fragment = variant.depthOnly ? "depth.frag" : fragmentShader_;
  auto program = gl::Program::build(
      shaderDir_, {{GL_VERTEX_SHADER, vertexShader_}, {GL_FRAGMENT_SHADER, fragment}}, defines, feedback);
  if (!program) return program.error();
  // Programs with transform feedback are for one-off captures; keep them apart.
  auto [it, inserted] = programs_.insert_or_assign(variant, std::move(program).value());
  (void)inserted;
  return &it->second;
}

std::vector<ShaderVariant> ShaderVariants::built() const {
  std::vector<ShaderVariant> out;
  for (const auto& entry : programs_) out.push_back(entry.first);
  return out;
}

namespace {

// glTF's material for both shading models: PBR reads metallic and roughness; the
// classic model turns roughness into a Blinn-Phong highlight.
void setMaterialUniforms(const gl::Program& pr, const MaterialData* material) {
  const float roughness = material ? material->roughnessFactor : 1.0f;
  pr.set("u_baseColorFactor", material ? material->baseColorFactor : glm::vec4(1.0f));
  pr.set("u_metallic", material ? material->metallicFactor : 0.0f);
  pr.set("u_roughness", roughness);
  pr.set("u_emissive", material ? material->emissiveFactor : glm::vec3(0.0f));
  pr.set("u_ambient", 0.1f);
  pr.set("u_diffuse", 0.9f);
  pr.set("u_specular", 0.5f * (1.0f - roughness));
  pr.set("u_shininess", 32.0f);
  pr.set("u_reflection", 0.0f);
}

template <typename T>
const gl::Buffer& addBuffer(GpuPrimitive& prim, const std::vector<T>& data) {
  prim.buffers.push_back(gl::Buffer::fromSpan(std::span<const T>(data)));
  return prim.buffers.back();
}

GpuPrimitive uploadPrimitive(const PrimitiveData& data) {
  GpuPrimitive prim;
  prim.vao = gl::VertexArray::create();
  prim.vertexCount = static_cast<GLsizei>(data.positions.size());
  prim.influences = data.influences;
  prim.material = data.material;
  prim.buffers.reserve(7);
  // One buffer per attribute: glTF keeps them apart and the shaders need only
  // some of them; missing normals and uvs get a constant attribute value.
  prim.vao.vertexBuffer(0, addBuffer(prim, data.positions), sizeof(glm::vec3));
  prim.vao.attribute(0, 0, 3, 0);
  if (!data.normals.empty()) {
    prim.vao.vertexBuffer(1, addBuffer(prim, data.normals), sizeof(glm::vec3));
    prim.vao.attribute(1, 1, 3, 0);
  } else {
    glVertexAttrib3f(1, 0.0f, 1.0f, 0.0f);
  }
  if (!data.uvs.empty()) {
    prim.vao.vertexBuffer(2, addBuffer(prim, data.uvs), sizeof(glm::vec2));
    prim.vao.attribute(2, 2, 2, 0);
  }
  if (data.influences > 0) {
    const GLsizei n = data.influences;
    prim.vao.vertexBuffer(3, addBuffer(prim, data.joints), n * GLsizei(sizeof(std::uint16_t)));
    prim.vao.vertexBuffer(4, addBuffer(prim, data.weights), n * GLsizei(sizeof(float)));
    prim.vao.integerAttribute(3, 3, 4, 0, GL_UNSIGNED_SHORT);
    prim.vao.attribute(4, 4, 4, 0);
    if (n == 8) {
      prim.vao.integerAttribute(5, 3, 4, 4 * sizeof(std::uint16_t), GL_UNSIGNED_SHORT);
      prim.vao.attribute(6, 4, 4, 4 * sizeof(float));
    }
  }
  if (!data.indices.empty()) {
    prim.vao.indexBuffer(addBuffer(prim, data.indices));
    prim.indexCount = static_cast<GLsizei>(data.indices.size());
  }
  return prim;
}

}  // namespace

Result<GpuModel> GpuModel::upload(const ModelData& model) {
  GpuModel gpu;
  for (const MeshData& mesh : model.meshes) {
    std::vector<GpuPrimitive> prims;
    for (const PrimitiveData& p : mesh.primitives) prims.push_back(uploadPrimitive(p));
    gpu.meshes_.push_back(std::move(prims));
  }
  for (const ImageData& image : model.images) {
    gl::Texture t = gl::Texture::create2D(GL_SRGB8_ALPHA8, image.image.width, image.image.height, 0);
    // glTF images are top row first and uv (0,0) is the top-left: upload as is.
    t.uploadRgba8(image.image.pixels.data());
    t.generateMipmaps();
    t.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    t.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gpu.images_.push_back(std::move(t));
  }
  for (const MaterialData& m : model.materials) gpu.materialImage_.push_back(m.baseColorImage);
  gpu.white_ = gl::Texture::create2D(GL_SRGB8_ALPHA8, 1, 1, 1);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  gpu.white_.uploadRgba8(white);
  return gpu;
}

const gl::Texture& GpuModel::baseColor(int material) const {
  if (material < 0 || material >= int(materialImage_.size())) return white_;
  const int image = materialImage_[size_t(material)];
  return image >= 0 && image < int(images_.size()) ? images_[size_t(image)] : white_;
}

Status drawModel(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                 const ModelFrame& frame) {
  // Camera-relative rendering: the camera offset is applied in double before the
  // matrices become float.
  const glm::dmat4 toCamera = glm::translate(glm::dmat4(1.0), -frame.cameraPosition);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = gpu.meshes()[size_t(node.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      const GpuPrimitive& prim = prims[p];
      const bool skinned = node.skin >= 0 && prim.influences > 0 && frame.skinMode != SkinMode::None;
      const MaterialData* material =
          prim.material >= 0 ? &model.materials[size_t(prim.material)] : nullptr;
      const bool textured = !frame.depthOnly && material && material->baseColorImage >= 0;
      const ShaderVariant variant{skinned ? prim.influences : 0, frame.skinMode, textured, frame.depthOnly};
      auto program = variants.get(variant);
      if (!program) return program.error();
      const gl::Program& pr = **program;
      pr.use();
      if (frame.setUniforms) frame.setUniforms(pr);
      if (!frame.depthOnly) setMaterialUniforms(pr, material);
      const glm::mat4 model4 =
          skinned ? glm::mat4(toCamera) : glm::mat4(toCamera * glm::dmat4(frame.nodeWorlds[n]));
      pr.set("u_model", model4);
      pr.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(model4)))));
      if (!frame.depthOnly) pr.set("u_viewProjection", frame.viewProjection);
      if (skinned) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, frame.skinBuffers[size_t(node.skin)].id());
      }
      if (!frame.depthOnly) gpu.baseColor(prim.material).bind(0);
      if (material && material->doubleSided) glDisable(GL_CULL_FACE);
      prim.vao.bind();
      const GLenum mode = GLenum(model.meshes[size_t(node.mesh)].primitives[p].mode);
      if (prim.indexCount > 0) {
        glDrawElements(mode, prim.indexCount, GL_UNSIGNED_INT, nullptr);
      } else {
        glDrawArrays(mode, 0, prim.vertexCount);
      }
      if (material && material->doubleSided) glEnable(GL_CULL_FACE);
    }
  }
  return Ok{};
}

}  // namespace engine
