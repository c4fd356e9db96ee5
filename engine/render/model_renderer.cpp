#include "render/model_renderer.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>

#include "asset/vertex_cache.h"
#include "core/sheen_table.h"
#include "gl/bindings.h"
#include "render/run_draws.h"
#include "render/skin_cache.h"

namespace engine {

std::string ShaderVariant::describe() const {
  std::string name = influences == 0 ? "static"
                                     : std::string(mode == SkinMode::DualQuat ? "dqs" : "lbs") +
                                           std::to_string(influences);
  if (morph) name += "+morph";
  if (textured) name += "+textured";
  if (normalMap) name += "+normalmap";
  if (metallicRoughnessTexture) name += "+mr";
  if (emissiveTexture) name += "+emissive";
  if (occlusion) name += "+occlusion";
  if (alphaMask) name += "+mask";
  if (uvTransform) name += "+uvtransform";
  if (vertexColor) name += "+vertexcolor";
  if (unlit) name += "+unlit";
  if (layers) name += "+layers";
  if (layerTextures) name += "+layertextures";
  if (transmission) name += "+transmission";
  if (clearcoatNormal) name += "+coatnormal";
  if (sheen) name += "+sheen";
  if (anisotropy) name += "+anisotropy";
  if (iridescence) name += "+iridescence";
  if (matte) name += "+matte";
  if (nearSunOnly) name += "+nearsun";
  if (oneSided) name += "+onesided";
  if (depthOnly) name += "+depth";
  if (surface == Surface::Out) name += "+surface";
  if (surface == Surface::In) name += "+fromsurface";
  return name;
}

bool ShaderVariant::deferrable() const {
  return !depthOnly && !normalMap && !metallicRoughnessTexture && !emissiveTexture && !occlusion && !alphaMask &&
         !uvTransform && !unlit && !vertexColor && !layers && !layerTextures && !transmission && !clearcoatNormal &&
         !sheen && !anisotropy && !iridescence && surface == Surface::None;
}

ShaderVariant ShaderVariant::shadingFromSurface() const {
  ShaderVariant v = *this;
  v.influences = 0;
  v.mode = SkinMode::Linear;
  v.morph = false;
  v.oneSided = false;
  v.nearSunOnly = false;
  v.surface = Surface::In;
  return v;
}

Result<const gl::Program*> ShaderVariants::get(const ShaderVariant& asked,
                                              const std::vector<std::string>& feedback) {
  ShaderVariant variant = asked;
  // A surface pass lights nothing: neither flag changes what it writes.
  const bool lights = !asked.depthOnly && asked.surface != ShaderVariant::Surface::Out;
  variant.matte = asked.matte && classic_ && lights;
  variant.nearSunOnly = asked.nearSunOnly && farSun_ && lights;
  variant.oneSided = asked.oneSided && facesCulled_ && !asked.depthOnly;
  // Programs with transform feedback (one-off captures) live in their own cache:
  // a pointer handed out for the plain variant stays valid and keeps its program.
  if (feedback.empty()) {
    if (auto it = programs_.find(variant); it != programs_.end()) return &it->second;
  } else if (auto it = feedbackPrograms_.find({variant, feedback}); it != feedbackPrograms_.end()) {
    return &it->second;
  }
  auto program = build(variant, feedback);
  if (!program) return program.error();
  gl::Program& stored = feedback.empty() ? programs_[variant] : feedbackPrograms_[{variant, feedback}];
  stored = std::move(program).value();
  return &stored;
}

Result<gl::Program> ShaderVariants::build(const ShaderVariant& variant, const std::vector<std::string>& feedback) const {
  std::vector<std::string> defines = defines_;
  if (variant.nearSunOnly) std::erase(defines, std::string(kFarSunDefine));
  if (variant.textured) defines.push_back("TEXTURED 1");
  if (variant.depthOnly) defines.push_back("DEPTH_ONLY 1");
  if (variant.normalMap) defines.push_back("NORMAL_MAP 1");
  if (variant.metallicRoughnessTexture) defines.push_back("MR_TEXTURE 1");
  if (variant.emissiveTexture) defines.push_back("EMISSIVE_TEXTURE 1");
  if (variant.occlusion) defines.push_back("OCCLUSION 1");
  if (variant.alphaMask) defines.push_back("ALPHA_MASK 1");
  if (variant.morph) defines.push_back("MORPH 1");
  if (variant.uvTransform) defines.push_back("UV_TRANSFORM 1");
  if (variant.vertexColor) defines.push_back("VERTEX_COLOR 1");
  if (variant.unlit) defines.push_back("UNLIT 1");
  if (variant.layers) defines.push_back("MATERIAL_LAYERS 1");
  if (variant.layerTextures) defines.push_back("LAYER_TEXTURES 1");
  if (variant.transmission) defines.push_back("TRANSMISSION 1");
  if (variant.clearcoatNormal) defines.push_back("CLEARCOAT_NORMAL 1");
  if (variant.sheen) defines.push_back("SHEEN 1");
  if (variant.anisotropy) defines.push_back("ANISOTROPY 1");
  if (variant.iridescence) defines.push_back("IRIDESCENCE 1");
  if (variant.matte) defines.push_back("CLASSIC_MATTE 1");
  if (variant.oneSided) defines.push_back("ONE_SIDED 1");
  if (variant.surface == ShaderVariant::Surface::Out) defines.push_back("SURFACE_OUT 1");
  if (variant.surface == ShaderVariant::Surface::In) defines.push_back("SURFACE_IN 1");
  if (variant.influences > 0) {
    defines.push_back("SKINNED 1");
    defines.push_back("INFLUENCES " + std::to_string(variant.influences));
    if (variant.mode == SkinMode::DualQuat) defines.push_back("DUAL_QUAT 1");
  }
  const std::string fragment = variant.depthOnly ? "depth.frag" : fragmentShader_;
  const std::string vertex = variant.surface == ShaderVariant::Surface::In ? "sky.vert" : vertexShader_;
  return gl::Program::build(shaderDir_, {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, defines,
                            feedback);
}

std::vector<ShaderVariant> ShaderVariants::built() const {
  std::vector<ShaderVariant> out;
  for (const auto& entry : programs_) out.push_back(entry.first);
  return out;
}

namespace {

// The classic model's highlight weight for a glTF material: its roughness turned into
// a Blinn-Phong highlight, none at roughness 1.
float classicSpecular(const MaterialData* material) {
  return 0.5f * (1.0f - (material ? material->roughnessFactor : 1.0f));
}

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
  pr.set("u_specular", classicSpecular(material));
  pr.set("u_shininess", 32.0f);
  pr.set("u_reflection", 0.0f);
  if (!material) return;
  if (material->layered()) {
    const MaterialLayers& l = material->layers;
    pr.set("u_iorF0", l.iorF0());
    pr.set("u_specularWeight", l.specular);
    pr.set("u_specularColor", l.specularColor);
    pr.set("u_clearcoat", l.clearcoat);
    pr.set("u_clearcoatRoughness", l.clearcoatRoughness);
    pr.set("u_transmission", l.transmission);
    pr.set("u_thickness", l.thickness);
    pr.set("u_ior", l.ior);
    pr.set("u_attenuationDistance", l.attenuationDistance);
    pr.set("u_attenuationColor", l.attenuationColor);
    pr.set("u_clearcoatNormalScale", l.clearcoatNormalScale);
    pr.set("u_sheenColor", l.sheenColor);
    pr.set("u_sheenRoughness", l.sheenRoughness);
    pr.set("u_anisotropy", l.anisotropy);
    pr.set("u_anisotropyRotation", l.anisotropyRotation);
    pr.set("u_iridescence", l.iridescence);
    pr.set("u_iridescenceIor", l.iridescenceIor);
    pr.set("u_iridescenceThickness", glm::vec2(l.iridescenceThicknessMin, l.iridescenceThicknessMax));
  }
  pr.set("u_normalScale", material->normalScale);
  pr.set("u_occlusionStrength", material->occlusionStrength);
  pr.set("u_alphaCutoff", material->alphaCutoff);
}

// Each slot's uv set and KHR_texture_transform matrix, for UV_TRANSFORM variants.
void setUvTransforms(const gl::Program& pr, const MaterialData& m) {
  using Names = std::array<std::string, kTextureSlots>;
  auto names = [](const char* array) {
    Names out;
    for (int i = 0; i < kTextureSlots; ++i) out[size_t(i)] = std::string(array) + "[" + std::to_string(i) + "]";
    return out;
  };
  static const Names kTransforms = names("u_uvTransform"), kTexCoords = names("u_texCoord");
  for (size_t i = 0; i < size_t(kTextureSlots); ++i) {
    pr.set(kTransforms[i].c_str(), m.textures[i].uvTransform);
    pr.set(kTexCoords[i].c_str(), m.textures[i].texCoord);
  }
}

// Texture units of common/material.glsl (gl/bindings.h), by TextureSlot.
constexpr GLuint kSlotUnits[kTextureSlots] = {gl::binding::kBaseColor,       gl::binding::kNormal,
                                              gl::binding::kMetallicRoughness, gl::binding::kEmissive,
                                              gl::binding::kOcclusion,         gl::binding::kSpecular,
                                              gl::binding::kSpecularColor,     gl::binding::kClearcoat,
                                              gl::binding::kClearcoatRoughness, gl::binding::kTransmission,
                                              gl::binding::kThickness,         gl::binding::kClearcoatNormal,
                                              gl::binding::kSheenColor,        gl::binding::kSheenRoughness,
                                              gl::binding::kAnisotropy,        gl::binding::kIridescence,
                                              gl::binding::kIridescenceThickness};

// Which slots the variant samples: the layer textures the material has, in a
// +layertextures variant (common/material.glsl's u_layerTextures says which).
std::array<bool, kTextureSlots> sampledSlots(const ShaderVariant& v, const MaterialData& m) {
  std::array<bool, kTextureSlots> sampled{v.textured, v.normalMap, v.metallicRoughnessTexture, v.emissiveTexture,
                                          v.occlusion};
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) sampled[size_t(i)] = v.layerTextures && m.image(TextureSlot(i)) >= 0;
  return sampled;
}

// Bit i - kFirstLayerSlot: layer slot i has a texture (common/material.glsl).
int layerTextureMask(const MaterialData& m) {
  int mask = 0;
  for (int i = kFirstLayerSlot; i < kTextureSlots; ++i) mask |= m.image(TextureSlot(i)) >= 0 ? 1 << (i - kFirstLayerSlot) : 0;
  return mask;
}

// Binds each sampled slot's image (colour slots as sRGB) and its glTF sampler, and
// a sheen's albedo table.
void bindMaterialTextures(const GpuModel& gpu, const MaterialData& m, const ShaderVariant& v) {
  if (v.sheen) gpu.sheenAlbedo().bind(gl::binding::kSheenAlbedo);
  const auto sampled = sampledSlots(v, m);
  for (int i = 0; i < kTextureSlots; ++i) {
    if (!sampled[size_t(i)]) continue;
    const TextureSlot slot = TextureSlot(i);
    gpu.image(m.image(slot), isSrgbSlot(slot)).bind(kSlotUnits[i]);
    gpu.sampler(m.textures[size_t(i)].sampler).bind(kSlotUnits[i]);
  }
}

// The material's textures, or for glTF's default material (none) the white base
// colour where the variant shades.
void bindMaterialOrWhite(const GpuModel& gpu, const MaterialData* m, const ShaderVariant& v) {
  if (m) {
    bindMaterialTextures(gpu, *m, v);
  } else if (!v.depthOnly) {
    gpu.image(-1, true).bind(gl::binding::kBaseColor);
  }
}

// The units' own texture parameters again, for whatever draws next (the scene's
// shapes and terrain bind textures on the same units without samplers).
void unbindMaterialSamplers(const ShaderVariant& v, const MaterialData& m) {
  const auto sampled = sampledSlots(v, m);
  for (int i = 0; i < kTextureSlots; ++i)
    if (sampled[size_t(i)]) gl::Sampler::unbind(kSlotUnits[i]);
}

template <typename T>
int addBuffer(GpuPrimitive& prim, const std::vector<T>& data) {
  prim.buffers.push_back(gl::Buffer::fromSpan(std::span<const T>(data)));
  return int(prim.buffers.size()) - 1;
}

// Appends a target-major attribute (PrimitiveData) vertex-major, so that the shader
// reads one vertex's displacements together, each padded to a vec4 (one load each in
// the shader, not three: llvmpipe checks every storage-buffer load); returns where
// the block starts (in vec4s), or -1 when no target moves the attribute.
int appendVertexMajor(std::vector<glm::vec4>& out, const std::vector<glm::vec3>& deltas, size_t vertices,
                      size_t targets) {
  if (deltas.empty()) return -1;
  const int start = int(out.size());
  for (size_t v = 0; v < vertices; ++v)
    for (size_t t = 0; t < targets; ++t) out.emplace_back(deltas[t * vertices + v], 0.0f);
  return start;
}

void uploadMorphTargets(const PrimitiveData& data, GpuPrimitive& prim) {
  if (data.morphTargets == 0) return;
  const size_t vertices = data.positions.size(), targets = size_t(data.morphTargets);
  std::vector<glm::vec4> deltas;
  prim.morphTargets = data.morphTargets;
  prim.morphPositions = appendVertexMajor(deltas, data.morphPositions, vertices, targets);
  prim.morphNormals = appendVertexMajor(deltas, data.morphNormals, vertices, targets);
  prim.morphTangents = appendVertexMajor(deltas, data.morphTangents, vertices, targets);
  // A buffer of at least one element: targets that move nothing still bind one.
  if (deltas.empty()) deltas.emplace_back(0.0f);
  prim.morphDeltas = gl::Buffer::fromSpan(std::span<const glm::vec4>(deltas));
  prim.morphDeltaTexture = gl::Texture::ofBuffer(prim.morphDeltas, GL_RGBA32F);
}

// The triangles of `indices` in vertex cache order when `reorder` (asset/vertex_cache.h).
std::vector<std::uint32_t> orderedIndices(const std::vector<std::uint32_t>& indices, std::size_t vertices, bool reorder) {
  return reorder ? orderForVertexCache(indices, vertices) : indices;
}

// Target-major displacements (PrimitiveData's morph arrays) in `split`'s vertex order.
std::vector<glm::vec3> targetsInSplitOrder(const std::vector<glm::vec3>& deltas, const RunSplit& split,
                                           std::size_t vertices, std::size_t targets) {
  std::vector<glm::vec3> out;
  if (deltas.empty()) return out;
  out.reserve(split.sourceVertex.size() * targets);
  for (std::size_t t = 0; t < targets; ++t)
    for (const std::uint32_t v : split.sourceVertex) out.push_back(deltas[t * vertices + v]);
  return out;
}

// `data`'s vertices (every attribute and morph displacement) as `split` copies them;
// its indices are left for the caller to set.
PrimitiveData verticesInSplitOrder(const PrimitiveData& data, const RunSplit& split) {
  PrimitiveData out = data;
  const std::size_t vertices = data.positions.size(), targets = std::size_t(data.morphTargets);
  const std::size_t influences = std::size_t(std::max(data.influences, 1));
  out.positions = inSplitOrder(data.positions, split);
  out.normals = inSplitOrder(data.normals, split);
  out.uvs = inSplitOrder(data.uvs, split);
  out.uvs1 = inSplitOrder(data.uvs1, split);
  out.colors = inSplitOrder(data.colors, split);
  out.tangents = inSplitOrder(data.tangents, split);
  out.joints = inSplitOrder(data.joints, split, influences);
  out.weights = inSplitOrder(data.weights, split, influences);
  out.morphPositions = targetsInSplitOrder(data.morphPositions, split, vertices, targets);
  out.morphNormals = targetsInSplitOrder(data.morphNormals, split, vertices, targets);
  out.morphTangents = targetsInSplitOrder(data.morphTangents, split, vertices, targets);
  return out;
}

// The full mesh's indices, then each level's, as the 32-bit index buffer holds them:
// into the split's vertices, the full mesh's through its runs, a level's through
// the first copy of each vertex (levels are drawn whole, not in runs).
std::vector<std::uint32_t> splitIndicesWithLevels(const RunSplit& split, const std::vector<std::vector<std::uint32_t>>& levels,
                                                  GpuPrimitive& prim) {
  std::vector<std::uint32_t> indices = indicesIntoCopies(split);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    prim.levels[l].firstIndex = GLsizei(indices.size());
    for (const std::uint32_t v : levels[l]) indices.push_back(split.firstCopy[v]);
  }
  return indices;
}

// GPU culling's clusters (render/cull_math.h): the full mesh's indices, then each
// level's, as they lie in the one index buffer. Bounded by the rest positions:
// a deforming mesh is culled by its instance's bounds alone.
void addClusters(const PrimitiveData& data, const std::vector<std::uint32_t>& indices, GpuPrimitive& prim) {
  prim.fullClusters = cull::appendClusters(data.positions, indices, 0, std::uint32_t(prim.indexCount), prim.clusters);
  for (GpuPrimitive::Level& level : prim.levels) {
    level.clusters = cull::appendClusters(data.positions, indices, std::uint32_t(level.firstIndex),
                                          std::uint32_t(level.indexCount), prim.clusters);
  }
}

// `prim`'s buffers of `data`'s vertex attributes, where the vertex array reads them.
void addVertexBuffers(const PrimitiveData& data, GpuPrimitive& prim) {
  // One buffer per attribute: glTF keeps them apart and the shaders need only
  // some of them.
  GpuPrimitive::Sources& in = prim.sources;
  in.positions = addBuffer(prim, data.positions);
  if (!data.normals.empty()) in.normals = addBuffer(prim, data.normals);
  if (!data.uvs.empty()) in.uvs = addBuffer(prim, data.uvs);
  if (!data.uvs1.empty()) in.uvs1 = addBuffer(prim, data.uvs1);
  if (!data.colors.empty()) in.colors = addBuffer(prim, data.colors);
  if (data.influences > 0) {
    in.joints = addBuffer(prim, data.joints);
    in.weights = addBuffer(prim, data.weights);
  }
  if (!data.tangents.empty()) in.tangents = addBuffer(prim, data.tangents);
  prim.hasTangents = in.tangents >= 0;
}

// An indexed triangle list: its full mesh (in vertex cache order when `reorder`)
// cut into runs, each with copies of its vertices; the 32-bit indices of it and of
// its levels into them, and the runs' own 16-bit ones.
void uploadInRuns(const PrimitiveData& source, const std::vector<MeshLod>* levels, bool reorder, GpuPrimitive& prim) {
  const std::size_t vertices = source.positions.size();
  RunSplit split = splitIntoRuns(orderedIndices(source.indices, vertices, reorder), vertices);
  std::vector<std::vector<std::uint32_t>> levelIndices;
  for (const MeshLod& level : levels ? *levels : std::vector<MeshLod>{}) {
    prim.levels.push_back({0, GLsizei(level.indices.size()), level.error, {}});
    levelIndices.push_back(orderedIndices(level.indices, vertices, reorder));
  }
  const PrimitiveData data = verticesInSplitOrder(source, split);
  const std::vector<std::uint32_t> indices = splitIndicesWithLevels(split, levelIndices, prim);
  addVertexBuffers(data, prim);
  prim.sources.indices = addBuffer(prim, indices);
  prim.sources.runIndices = addBuffer(prim, runIndexBuffer(split));
  prim.vertexCount = GLsizei(data.positions.size());
  prim.indexCount = GLsizei(source.indices.size());
  prim.runs = std::move(split.runs);
  prim.sourceVertex = std::move(split.sourceVertex);
  addClusters(data, indices, prim);
  uploadMorphTargets(data, prim);
}

// Any other primitive: its vertices as they are, and its indices.
void uploadWhole(const PrimitiveData& data, GpuPrimitive& prim) {
  addVertexBuffers(data, prim);
  if (!data.indices.empty()) prim.sources.indices = addBuffer(prim, data.indices);
  prim.vertexCount = GLsizei(data.positions.size());
  prim.indexCount = GLsizei(data.indices.size());
  uploadMorphTargets(data, prim);
}

GpuPrimitive uploadPrimitive(const PrimitiveData& data, const std::vector<MeshLod>* levels, bool reorder) {
  GpuPrimitive prim;
  prim.influences = data.influences;
  prim.material = data.material;
  if (isIndexedTriangleList(data)) {  // drawn in runs (asset/vertex_runs.h)
    uploadInRuns(data, levels, reorder, prim);
  } else {
    uploadWhole(data, prim);
  }
  prim.vao = gl::VertexArray::create();
  attachAttributes(prim, prim.vao, nullptr);
  if (!data.positions.empty()) {
    glm::vec3 lo(data.positions[0]), hi(data.positions[0]);
    for (const glm::vec3& p : data.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    prim.center = (lo + hi) * 0.5f;
  }
  return prim;
}

gl::Texture uploadImage(const Image& image, GLenum format) {
  gl::Texture t = gl::Texture::create2D(format, image.width, image.height, 0);
  // glTF images are top row first and uv (0,0) is the top-left: upload as is.
  t.uploadRgba8(image.pixels.data());
  t.generateMipmaps();
  t.parameter(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  t.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  return t;
}

const MaterialData* materialOf(const ModelData& model, int material) {
  return material >= 0 && material < int(model.materials.size()) ? &model.materials[size_t(material)] : nullptr;
}

bool isBlend(const ModelData& model, int material) {
  const MaterialData* m = materialOf(model, material);
  return m && m->alphaMode == AlphaMode::Blend;
}

// The frame's weights for node `node`'s MORPH draw.
Status bindNodeMorphTargets(const gl::Program& pr, const GpuPrimitive& prim, const ModelFrame& frame, size_t node) {
  if (frame.morphWeights == nullptr || node >= frame.morphFirst.size() || frame.morphFirst[node] < 0)
    return makeError("node " + std::to_string(node) + ": has morph targets but the frame has no weights for it");
  bindMorphTargets(pr, prim, *frame.morphWeights, frame.morphFirst[node]);
  return Ok{};
}

// Clockwise faces front where counter-clockwise ones did, and back.
void flipFrontFace() {
  GLint face = GL_CCW;
  glGetIntegerv(GL_FRONT_FACE, &face);
  glFrontFace(face == GL_CCW ? GL_CW : GL_CCW);
}

// Level `level`'s first index and count in the 32-bit indices (-1: the full mesh's).
std::pair<GLsizei, GLsizei> levelRange(const GpuPrimitive& prim, int level) {
  if (level < 0) return {0, prim.indexCount};
  return {prim.levels[size_t(level)].firstIndex, prim.levels[size_t(level)].indexCount};
}

// Runs `draw` with `prim`'s 32-bit indices bound to the bound vertex array, which
// otherwise reads its runs' 16-bit ones (when it has runs).
template <typename Draw>
void withPrimitiveIndices(const GpuPrimitive& prim, Draw draw) {
  if (prim.sources.runIndices < 0) return draw();
  withWholeIndices(prim.buffers[size_t(prim.sources.indices)], prim.buffers[size_t(prim.sources.runIndices)], draw);
}

// Draws primitive `p` of node `n` (each of its instances), with whatever blend
// state is set.
Status drawPrimitive(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu, const ModelFrame& frame,
                     size_t n, size_t p) {
  const NodeData& node = model.nodes[n];
  const GpuPrimitive& prim = gpu.meshes()[size_t(node.mesh)][p];
  const PrimitiveData& data = model.meshes[size_t(node.mesh)].primitives[p];
  const gl::VertexArray* cached = frame.skinCache ? frame.skinCache->vertexArray(int(n), int(p)) : nullptr;
  ShaderVariant variant = primitiveVariant(model, node, data, frame.skinMode, frame.depthOnly, cached != nullptr);
  variant.nearSunOnly = frame.nearSunOnly;
  variant.surface = frame.surface;
  const MaterialData* material = materialOf(model, prim.material);
  auto program = variants.get(variant);
  if (!program) return program.error();
  const gl::Program& pr = **program;
  pr.use();
  if (frame.setUniforms) frame.setUniforms(pr);
  if (!frame.depthOnly) {
    setMaterialUniforms(pr, material);
  } else if (variant.alphaMask) {
    pr.set("u_baseColorFactor", material->baseColorFactor);
    pr.set("u_alphaCutoff", material->alphaCutoff);
  }
  if (variant.uvTransform) setUvTransforms(pr, *material);
  if (variant.layerTextures) pr.set("u_layerTextures", layerTextureMask(*material));
  // scene.vert's tiling of analytic shapes: a program may be shared with them.
  pr.set("u_uvScale", glm::vec2(1.0f));
  if (!frame.depthOnly) pr.set("u_viewProjection", frame.viewProjection);
  if (variant.influences > 0) {
    frame.skinPalettes[size_t(node.skin)].bind(gl::binding::kSkinPalette);
  }
  if (variant.morph) {
    if (auto s = bindNodeMorphTargets(pr, prim, frame, n); !s) return makeError(model.path + ": " + s.error().message);
  }
  bindMaterialOrWhite(gpu, material, variant);
  // Double-sided: no culling for this draw; the caller's setting is restored (the
  // point-light shadow pass draws everything without culling).
  const bool twoSided = material && material->doubleSided && glIsEnabled(GL_CULL_FACE);
  if (twoSided) glDisable(GL_CULL_FACE);
  (cached ? *cached : prim.vao).bind();
  // EXT_mesh_gpu_instancing: one draw per instance, each with its own u_model.
  // Chosen over glDrawElementsInstanced with an instance-matrix buffer because
  // every shader variant (lit, depth-only, point-shadow, skin-cached) and the
  // sorted scene draw items then work unchanged; the cost is one draw call per
  // instance, which is fine for the sample's 125 boxes but not for forests.
  // Skinned nodes have no instances (the loader drops them), so they draw once.
  const std::vector<glm::mat4> models = primitiveInstanceModels(model, frame, int(n), data.influences);
  const bool indirect = !frame.indirect.empty() && hasClusters(prim, GLenum(data.mode));
  for (size_t i = 0; i < models.size(); ++i) {
    const glm::mat4& model4 = models[i];
    pr.set("u_model", model4);
    pr.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(model4)))));
    // glTF: a world transform with a negative determinant mirrors the mesh, which
    // turns its counter-clockwise faces clockwise; the pass's front face is
    // flipped for the draw (NegativeScaleTest's scale -1 row) and put back.
    const bool mirrored = glm::determinant(glm::mat3(model4)) < 0.0f;
    if (mirrored) flipFrontFace();
    drawMesh(prim, GLenum(data.mode), frame.lodBudget, indirect ? &frame.indirect[i] : nullptr);
    if (mirrored) flipFrontFace();
  }
  if (twoSided) glEnable(GL_CULL_FACE);
  if (material) unbindMaterialSamplers(variant, *material);
  return Ok{};
}

}  // namespace

void drawMesh(const GpuPrimitive& prim, GLenum mode, float lodBudget, const IndirectDraw* indirect) {
  if (indirect) {
    withPrimitiveIndices(prim, [&] {
      glMultiDrawElementsIndirect(mode, GL_UNSIGNED_INT, reinterpret_cast<const void*>(indirect->offset),
                                  indirect->count, 0);
    });
  } else if (prim.indexCount > 0) {
    const int level = levelIndexWithin(prim, lodBudget);
    if (level < 0 && !prim.runs.empty()) return drawRuns(prim.runs, mode);
    const std::pair<GLsizei, GLsizei> range = levelRange(prim, level);  // first index, count
    withPrimitiveIndices(prim, [&] {
      glDrawElements(mode, range.second, GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(std::uintptr_t(range.first) * sizeof(std::uint32_t)));
    });
  } else {
    glDrawArrays(mode, 0, prim.vertexCount);
  }
}

int levelIndexWithin(const GpuPrimitive& prim, float budget) { return coarsestWithin(prim.levels, budget); }

std::vector<glm::mat4> primitiveInstanceModels(const ModelData& model, const ModelFrame& frame, int node,
                                               int influences) {
  const NodeData& n = model.nodes[size_t(node)];
  // Camera-relative rendering: the camera offset is applied in double before the
  // matrices become float.
  const glm::dmat4 toCamera = glm::translate(glm::dmat4(1.0), -frame.cameraPosition);
  const bool skinned = skinnedBy(n, influences, frame.skinMode);
  const glm::dmat4 placed = skinned ? toCamera * frame.root : toCamera * glm::dmat4(frame.nodeWorlds[size_t(node)]);
  std::vector<glm::mat4> out;
  for (const glm::mat4& instance : meshInstances(n)) out.push_back(glm::mat4(placed * glm::dmat4(instance)));
  return out;
}

void attachAttributes(const GpuPrimitive& prim, const gl::VertexArray& vao, const gl::Buffer* deformed) {
  const GpuPrimitive::Sources& in = prim.sources;
  auto buffer = [&prim](int index) -> const gl::Buffer& { return prim.buffers[size_t(index)]; };
  // Bindings: 0 positions, 1 normals, 2 uvs, 3 joints, 4 weights, 5 tangents,
  // 6 TEXCOORD_1; locations as model.vert and scene.vert read them.
  if (deformed) {
    constexpr GLsizei stride = 3 * sizeof(glm::vec4);  // skin.comp's DeformedVertex
    vao.vertexBuffer(0, *deformed, stride);
    vao.attribute(0, 0, 3, 0);
    vao.attribute(1, 0, 3, sizeof(glm::vec4));
    if (prim.hasTangents) vao.attribute(7, 0, 4, 2 * sizeof(glm::vec4));
  } else {
    vao.vertexBuffer(0, buffer(in.positions), sizeof(glm::vec3));
    vao.attribute(0, 0, 3, 0);
    if (in.normals >= 0) {
      vao.vertexBuffer(1, buffer(in.normals), sizeof(glm::vec3));
      vao.attribute(1, 1, 3, 0);
    } else {
      glVertexAttrib3f(1, 0.0f, 1.0f, 0.0f);  // missing normals: a constant (current) value
    }
    if (in.tangents >= 0) {
      vao.vertexBuffer(5, buffer(in.tangents), sizeof(glm::vec4));
      vao.attribute(7, 5, 4, 0);
    }
    if (in.joints >= 0) {
      const GLsizei n = prim.influences;
      vao.vertexBuffer(3, buffer(in.joints), n * GLsizei(sizeof(std::uint16_t)));
      vao.vertexBuffer(4, buffer(in.weights), n * GLsizei(sizeof(float)));
      vao.integerAttribute(3, 3, 4, 0, GL_UNSIGNED_SHORT);
      vao.attribute(4, 4, 4, 0);
      if (n == 8) {
        vao.integerAttribute(5, 3, 4, 4 * sizeof(std::uint16_t), GL_UNSIGNED_SHORT);
        vao.attribute(6, 4, 4, 4 * sizeof(float));
      }
    }
  }
  if (in.uvs >= 0) {
    vao.vertexBuffer(2, buffer(in.uvs), sizeof(glm::vec2));
    vao.attribute(2, 2, 2, 0);
  }
  if (in.uvs1 >= 0) {
    vao.vertexBuffer(6, buffer(in.uvs1), sizeof(glm::vec2));
    vao.attribute(8, 6, 2, 0);
  }
  if (in.colors >= 0) {
    vao.vertexBuffer(7, buffer(in.colors), sizeof(glm::vec4));
    vao.attribute(9, 7, 4, 0);
  }
  if (in.runIndices >= 0) {
    vao.indexBuffer(buffer(in.runIndices));
  } else if (in.indices >= 0) {
    vao.indexBuffer(buffer(in.indices));
  }
}

void bindMorphTargets(const gl::Program& program, const GpuPrimitive& prim, const gl::Buffer& weights, int first) {
  glBindTextureUnit(gl::binding::kMorphDeltas, prim.morphDeltaTexture.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kMorphWeightsBuffer, weights.id());
  program.set("u_morphTargets", prim.morphTargets);
  program.set("u_morphFirst", first);
  program.set("u_morphPositions", prim.morphPositions);
  program.set("u_morphNormals", prim.morphNormals);
  program.set("u_morphTangents", prim.morphTangents);
}

ShaderVariant primitiveVariant(const ModelData& model, const NodeData& node, const PrimitiveData& prim,
                               SkinMode mode, bool depthOnly, bool cached) {
  ShaderVariant v;
  v.influences = skinnedBy(node, prim.influences, mode) && !cached ? prim.influences : 0;
  // The blend only matters to skinning code: every static variant is one program,
  // whichever mode (or cache) the model draws with.
  v.mode = v.influences > 0 ? mode : SkinMode::Linear;
  v.morph = prim.morphTargets > 0 && !cached;
  v.depthOnly = depthOnly;
  const MaterialData* m = materialOf(model, prim.material);
  const bool colored = !prim.colors.empty();  // COLOR_0 multiplies the base colour
  v.vertexColor = colored && !depthOnly;
  v.matte = classicSpecular(m) <= 0.0f;
  v.oneSided = !m || !m->doubleSided;  // glTF's default material is one-sided
  if (!m) return v;
  v.alphaMask = m->alphaMode == AlphaMode::Mask;
  // A shadow pass needs the material only to cut out MASK holes.
  if (depthOnly) {
    v.textured = v.alphaMask && m->baseColorImage >= 0;
    v.vertexColor = colored && v.alphaMask;
  } else if (m->unlit) {
    // Nothing but the base colour is read: no variant for the other slots.
    v.textured = m->baseColorImage >= 0;
    v.unlit = true;
  } else {
    v.textured = m->baseColorImage >= 0;
    v.normalMap = m->normalImage >= 0 && !prim.tangents.empty();
    v.metallicRoughnessTexture = m->metallicRoughnessImage >= 0;
    v.emissiveTexture = m->emissiveImage >= 0;
    v.occlusion = m->occlusionImage >= 0;
    v.layers = m->layered();
    v.layerTextures = m->hasLayerTextures();
    v.transmission = m->layers.transmissive();
    v.clearcoatNormal = m->layers.clearcoat > 0.0f && m->image(TextureSlot::ClearcoatNormal) >= 0 && !prim.tangents.empty();
    v.sheen = m->layers.sheen();
    v.anisotropy = m->layers.anisotropy > 0.0f && !prim.tangents.empty();
    v.iridescence = m->layers.iridescence > 0.0f;
  }
  const auto sampled = sampledSlots(v, *m);
  for (int i = 0; i < kTextureSlots; ++i) v.uvTransform |= sampled[size_t(i)] && m->textures[size_t(i)].transformsUv();
  return v;
}

Result<GpuModel> GpuModel::upload(const ModelData& model, const UploadOptions& options) {
  GpuModel gpu;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    std::vector<GpuPrimitive> prims;
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) {
      const std::vector<MeshLod>* levels = options.levels ? &(*options.levels)[m][k] : nullptr;
      const PrimitiveData& data = model.meshes[m].primitives[k];
      prims.push_back(uploadPrimitive(data, levels, mayReorderTriangles(model, data)));
    }
    gpu.meshes_.push_back(std::move(prims));
  }
  std::vector<char> srgb(model.images.size(), 0), linear(model.images.size(), 0);
  auto use = [](std::vector<char>& used, int image) {
    if (image >= 0 && image < int(used.size())) used[size_t(image)] = 1;
  };
  for (const MaterialData& m : model.materials) {
    for (int i = 0; i < kTextureSlots; ++i) use(isSrgbSlot(TextureSlot(i)) ? srgb : linear, m.image(TextureSlot(i)));
  }
  gpu.srgbImages_.resize(model.images.size());
  gpu.linearImages_.resize(model.images.size());
  for (size_t i = 0; i < model.images.size(); ++i) {
    const Image& image = model.images[i].image;
    if (srgb[i]) gpu.srgbImages_[i] = uploadImage(image, GL_SRGB8_ALPHA8);
    if (linear[i]) gpu.linearImages_[i] = uploadImage(image, GL_RGBA8);
  }
  for (const MaterialData& m : model.materials) {
    for (const TextureSlotData& slot : m.textures) {
      if (gpu.samplers_.count(slot.sampler)) continue;
      gl::Sampler sampler = gl::Sampler::create();
      sampler.parameter(GL_TEXTURE_WRAP_S, GLint(slot.sampler.wrapS));
      sampler.parameter(GL_TEXTURE_WRAP_T, GLint(slot.sampler.wrapT));
      sampler.parameter(GL_TEXTURE_MAG_FILTER, GLint(slot.sampler.magFilter));
      sampler.parameter(GL_TEXTURE_MIN_FILTER, GLint(slot.sampler.minFilter));
      gpu.samplers_.emplace(slot.sampler, std::move(sampler));
    }
  }
  const bool sheen = std::any_of(model.materials.begin(), model.materials.end(),
                                 [](const MaterialData& m) { return m.layers.sheen(); });
  // Filtered as SheenTable::lookup filters it.
  if (sheen) gpu.sheenAlbedo_ = gl::Texture::table(GL_R32F, GL_RED, sheenTable().size, sheenTable().texels.data());
  gpu.white_ = gl::Texture::create2D(GL_SRGB8_ALPHA8, 1, 1, 1);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  gpu.white_.uploadRgba8(white);
  return gpu;
}

const gl::Texture& GpuModel::image(int image, bool srgb) const {
  const auto& images = srgb ? srgbImages_ : linearImages_;
  if (image < 0 || image >= int(images.size()) || images[size_t(image)].id() == 0) return white_;
  return images[size_t(image)];
}

const gl::Sampler& GpuModel::sampler(const SamplerData& settings) const {
  // Every material slot's settings were made on upload.
  return samplers_.at(settings);
}

std::vector<BlendPrimitive> blendPrimitives(const ModelData& model, const GpuModel& gpu,
                                            std::span<const glm::mat4> nodeWorlds) {
  std::vector<BlendPrimitive> out;
  for (size_t n = 0; n < model.nodes.size() && n < nodeWorlds.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = gpu.meshes()[size_t(node.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      if (!isBlend(model, prims[p].material)) continue;
      // A skinned primitive is placed by its joints, not its node; the node's
      // place is close enough to order whole primitives. EXT_mesh_gpu_instancing
      // instances of a BLEND primitive are sorted as one, at the node, and drawn
      // in the file's order (not back to front among themselves).
      const glm::dvec3 center(nodeWorlds[n] * glm::vec4(prims[p].center, 1.0f));
      out.push_back({int(n), int(p), glm::length(center)});
    }
  }
  return out;
}

Status drawBlendPrimitive(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                          const ModelFrame& frame, const BlendPrimitive& primitive) {
  glEnable(GL_BLEND);
  // Over, in the target's linear colour; the target's alpha is left alone.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glDepthMask(GL_FALSE);
  Status status = drawPrimitive(variants, model, gpu, frame, size_t(primitive.node), size_t(primitive.primitive));
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  return status;
}

Status drawModelPrimitive(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                          const ModelFrame& frame, int node, int primitive) {
  return drawPrimitive(variants, model, gpu, frame, size_t(node), size_t(primitive));
}

Status shadeModelSurface(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu, int material,
                         const ShaderVariant& shading, const std::function<void(const gl::Program&)>& setUniforms,
                         const glm::mat4& inverseViewProjection) {
  const MaterialData* m = materialOf(model, material);
  auto program = variants.get(shading);
  if (!program) return program.error();
  const gl::Program& pr = **program;
  pr.use();
  if (setUniforms) setUniforms(pr);
  setMaterialUniforms(pr, m);
  pr.set("u_inverseViewProjection", inverseViewProjection);
  bindMaterialOrWhite(gpu, m, shading);
  glDrawArrays(GL_TRIANGLES, 0, 3);  // sky.vert's full-screen triangle
  if (m) unbindMaterialSamplers(shading, *m);
  return Ok{};
}

Status drawModel(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                 const ModelFrame& frame) {
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = gpu.meshes()[size_t(node.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      if (isBlend(model, prims[p].material)) continue;
      if (auto s = drawPrimitive(variants, model, gpu, frame, n, p); !s) return s;
    }
  }
  if (!frame.includeBlend || frame.depthOnly) return Ok{};
  // Camera-relative node worlds: the camera is at cameraPosition.
  std::vector<glm::mat4> relative(frame.nodeWorlds.begin(), frame.nodeWorlds.end());
  for (glm::mat4& m : relative) m[3] -= glm::vec4(glm::vec3(frame.cameraPosition), 0.0f);
  auto blend = blendPrimitives(model, gpu, relative);
  std::stable_sort(blend.begin(), blend.end(),
                   [](const BlendPrimitive& a, const BlendPrimitive& b) { return a.distance > b.distance; });
  for (const BlendPrimitive& b : blend) {
    if (auto s = drawBlendPrimitive(variants, model, gpu, frame, b); !s) return s;
  }
  return Ok{};
}

}  // namespace engine
