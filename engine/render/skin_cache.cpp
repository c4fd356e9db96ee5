#include "render/skin_cache.h"

#include <algorithm>

#include "gl/bindings.h"

namespace engine {

namespace {

// skin.comp's DeformedVertex: position, normal, tangent, a vec4 each.
constexpr std::size_t kDeformedVertexBytes = 3 * 4 * sizeof(float);
constexpr GLuint kGroupSize = 64;  // skin.comp's local_size_x

// Source attribute `index` of `prim` (-1: absent) as skin.comp reads it.
gl::Texture sourceTexture(const GpuPrimitive& prim, int index, GLenum format) {
  return index >= 0 ? gl::Texture::ofBuffer(prim.buffers[size_t(index)], format) : gl::Texture{};
}

}  // namespace

std::string SkinPrograms::Variant::describe() const {
  std::string out = influences > 0 ? std::string(mode == SkinMode::DualQuat ? "dqs" : "lbs") + std::to_string(influences)
                                   : std::string("unskinned");
  if (morph) out += "+morph";
  if (normals) out += "+normals";
  if (tangents) out += "+tangents";
  return out;
}

Result<const gl::Program*> SkinPrograms::get(const Variant& variant) {
  if (auto it = programs_.find(variant); it != programs_.end()) return &it->second;
  std::vector<std::string> defines;
  if (variant.influences > 0) {
    defines.push_back("SKINNED 1");
    defines.push_back("INFLUENCES " + std::to_string(variant.influences));
    if (variant.mode == SkinMode::DualQuat) defines.push_back("DUAL_QUAT 1");
  }
  if (variant.morph) defines.push_back("MORPH 1");
  if (variant.normals) defines.push_back("HAS_NORMALS 1");
  if (variant.tangents) defines.push_back("NORMAL_MAP 1");
  auto program = gl::Program::build(shaderDir_, {{GL_COMPUTE_SHADER, "skin.comp"}}, defines);
  if (!program) return program.error();
  return &programs_.emplace(variant, std::move(program).value()).first->second;
}

std::vector<SkinPrograms::Variant> SkinPrograms::built() const {
  std::vector<Variant> out;
  for (const auto& entry : programs_) out.push_back(entry.first);
  return out;
}

bool deforms(const NodeData& node, const PrimitiveData& prim) {
  return (node.skin >= 0 && prim.influences > 0) || prim.morphTargets > 0;
}

SkinCache SkinCache::create(const ModelData& model, const GpuModel& gpu) {
  SkinCache cache;
  for (int n = 0; n < int(model.nodes.size()); ++n) {
    const NodeData& node = model.nodes[size_t(n)];
    if (node.mesh < 0) continue;
    const auto& prims = model.meshes[size_t(node.mesh)].primitives;
    for (int p = 0; p < int(prims.size()); ++p) {
      if (!deforms(node, prims[size_t(p)])) continue;
      const GpuPrimitive& source = gpu.meshes()[size_t(node.mesh)][size_t(p)];
      Entry entry;
      entry.node = n;
      entry.primitive = p;
      // At least one vertex: a buffer may not be empty.
      entry.output = gl::Buffer::create(std::max<std::size_t>(1, size_t(source.vertexCount)) * kDeformedVertexBytes,
                                        nullptr, 0);
      entry.vao = gl::VertexArray::create();
      attachAttributes(source, entry.vao, &entry.output);
      // In skin.comp's unit order: positions, normals, tangents, joints (4 uint16
      // a texel), weights (4 floats a texel).
      entry.sources = {sourceTexture(source, source.sources.positions, GL_RGB32F),
                       sourceTexture(source, source.sources.normals, GL_RGB32F),
                       sourceTexture(source, source.sources.tangents, GL_RGBA32F),
                       sourceTexture(source, source.sources.joints, GL_RGBA16UI),
                       sourceTexture(source, source.sources.weights, GL_RGBA32F)};
      cache.entries_.push_back(std::move(entry));
    }
  }
  return cache;
}

Status SkinCache::run(SkinPrograms& programs, const ModelData& model, const GpuModel& gpu, const Inputs& inputs,
                      const Entry& entry) {
  const NodeData& node = model.nodes[size_t(entry.node)];
  const GpuPrimitive& prim = gpu.meshes()[size_t(node.mesh)][size_t(entry.primitive)];
  const bool skinned = skinnedBy(node, prim.influences, inputs.mode);
  SkinPrograms::Variant variant{skinned ? prim.influences : 0, inputs.mode, prim.morphTargets > 0,
                                prim.sources.normals >= 0, prim.hasTangents};
  auto program = programs.get(variant);
  if (!program) return makeError(model.path + ": skin cache: " + program.error().message);
  const gl::Program& pr = **program;
  pr.use();
  pr.set("u_vertexCount", prim.vertexCount);
  constexpr unsigned kUnits[] = {gl::binding::kSkinPositions, gl::binding::kSkinNormals, gl::binding::kSkinTangents,
                                 gl::binding::kSkinJoints, gl::binding::kSkinWeights};
  for (size_t i = 0; i < entry.sources.size(); ++i)
    if (entry.sources[i]) entry.sources[i].bind(kUnits[i]);
  if (skinned) {
    inputs.skinPalettes[size_t(node.skin)].bind(gl::binding::kSkinPalette);
  }
  if (variant.morph) {
    const int first = size_t(entry.node) < inputs.morphFirst.size() ? inputs.morphFirst[size_t(entry.node)] : -1;
    if (!inputs.morphWeights || first < 0)
      return makeError(model.path + ": node " + std::to_string(entry.node) + ": has morph targets but no weights");
    bindMorphTargets(pr, prim, *inputs.morphWeights, first);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kSkinOutput, entry.output.id());
  glDispatchCompute((GLuint(prim.vertexCount) + kGroupSize - 1) / kGroupSize, 1, 1);
  verticesDeformed_ += prim.vertexCount;
  return Ok{};
}

Status SkinCache::update(SkinPrograms& programs, const ModelData& model, const GpuModel& gpu, const Inputs& inputs) {
  verticesDeformed_ = 0;
  for (const Entry& entry : entries_) {
    if (auto s = run(programs, model, gpu, inputs, entry); !s) return s;
  }
  // The passes read the output as vertex attributes.
  if (!entries_.empty()) glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return Ok{};
}

const SkinCache::Entry* SkinCache::find(int node, int primitive) const {
  auto it = std::lower_bound(entries_.begin(), entries_.end(), std::pair(node, primitive),
                             [](const Entry& e, const std::pair<int, int>& key) {
                               return std::pair(e.node, e.primitive) < key;
                             });
  if (it == entries_.end() || it->node != node || it->primitive != primitive) return nullptr;
  return &*it;
}

const gl::VertexArray* SkinCache::vertexArray(int node, int primitive) const {
  const Entry* e = find(node, primitive);
  return e ? &e->vao : nullptr;
}

const gl::Buffer* SkinCache::output(int node, int primitive) const {
  const Entry* e = find(node, primitive);
  return e ? &e->output : nullptr;
}

std::size_t SkinCache::bytes() const {
  std::size_t total = 0;
  for (const Entry& e : entries_) total += e.output.size();
  return total;
}

}  // namespace engine
