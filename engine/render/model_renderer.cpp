// Drawing models: each primitive with its variant, material, morph targets and
// instances, the BLEND ones sorted back to front. Variants, uploads and material
// binding are in model_renderer_*.cpp, which share model_renderer_impl.h.
#include "render/model_renderer.h"

#include <algorithm>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>

#include "gl/bindings.h"
#include "render/model_renderer_impl.h"
#include "render/run_draws.h"
#include "render/skin_cache.h"

namespace engine {
namespace {

bool isBlend(const GpuModel& gpu, int material) { return gpu.material(material).blends(); }

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
  const bool gltfDefault = materialOf(model, prim.material) == nullptr;
  const SceneMaterial& material = gpu.material(prim.material);
  auto program = variants.get(variant);
  if (!program) return program.error();
  const gl::Program& pr = **program;
  pr.use();
  if (frame.setUniforms) frame.setUniforms(pr);
  if (!frame.depthOnly) {
    setMaterialUniforms(pr, material);
  } else if (variant.alphaMask) {
    pr.set("u_baseColorFactor", material.baseColor());
    pr.set("u_alphaCutoff", material.alphaCutoff);
  }
  if (variant.uvTransform) setUvTransforms(pr, material);
  if (variant.layerTextures) pr.set("u_layerTextures", layerTextureMask(material));
  // scene.vert's tiling of analytic shapes: a program may be shared with them.
  pr.set("u_uvScale", glm::vec2(1.0f));
  if (variant.influences > 0) {
    frame.skinPalettes[size_t(node.skin)].bind(gl::binding::kSkinPalette);
  }
  if (variant.morph) {
    if (auto s = bindNodeMorphTargets(pr, prim, frame, n); !s) return makeError(model.path + ": " + s.error().message);
  }
  bindMaterialOrWhite(gpu, gltfDefault ? nullptr : &material, variant);
  // Double-sided: no culling for this draw; the caller's setting is restored (the
  // point-light shadow pass draws everything without culling).
  const bool twoSided = material.doubleSided && glIsEnabled(GL_CULL_FACE);
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
  if (!gltfDefault) unbindMaterialSamplers(variant, material);
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

void bindMorphTargets(const gl::Program& program, const GpuPrimitive& prim, const gl::Buffer& weights, int first) {
  glBindTextureUnit(gl::binding::kMorphDeltas, prim.morphDeltaTexture.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kMorphWeightsBuffer, weights.id());
  program.set("u_morphTargets", prim.morphTargets);
  program.set("u_morphFirst", first);
  program.set("u_morphPositions", prim.morphPositions);
  program.set("u_morphNormals", prim.morphNormals);
  program.set("u_morphTangents", prim.morphTangents);
}

std::vector<BlendPrimitive> blendPrimitives(const ModelData& model, const GpuModel& gpu,
                                            std::span<const glm::mat4> nodeWorlds) {
  std::vector<BlendPrimitive> out;
  for (size_t n = 0; n < model.nodes.size() && n < nodeWorlds.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = gpu.meshes()[size_t(node.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      if (!isBlend(gpu, prims[p].material)) continue;
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
  const bool gltfDefault = materialOf(model, material) == nullptr;
  const SceneMaterial& m = gpu.material(material);
  auto program = variants.get(shading);
  if (!program) return program.error();
  const gl::Program& pr = **program;
  pr.use();
  if (setUniforms) setUniforms(pr);
  setMaterialUniforms(pr, m);
  pr.set("u_inverseViewProjection", inverseViewProjection);
  bindMaterialOrWhite(gpu, gltfDefault ? nullptr : &m, shading);
  glDrawArrays(GL_TRIANGLES, 0, 3);  // sky.vert's full-screen triangle
  if (!gltfDefault) unbindMaterialSamplers(shading, m);
  return Ok{};
}

Status drawModel(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                 const ModelFrame& frame) {
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const NodeData& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const auto& prims = gpu.meshes()[size_t(node.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      if (isBlend(gpu, prims[p].material)) continue;
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
