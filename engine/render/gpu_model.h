#pragma once
// A glTF model on the GPU: its primitives' buffers (runs, levels of detail,
// clusters, morph displacements), its images and samplers and its material table,
// and the rules the draws, the variants and the skin cache share (which
// primitives skin, the LBS palette's layout, the vertex arrays). What draws them
// is render/model_renderer.h.
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "asset/mesh_lod.h"
#include "asset/model_data.h"
#include "asset/vertex_runs.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/cull_math.h"
#include "scene/materials.h"

namespace engine {

// None draws skinned meshes in their bind pose with the static shader.
enum class SkinMode { Linear, DualQuat, None };

struct GpuPrimitive {
  gl::VertexArray vao;
  std::vector<gl::Buffer> buffers;
  GLsizei vertexCount = 0;  // in the buffers: an indexed triangle list's are its runs' copies
  GLsizei indexCount = 0;  // 0: not indexed
  int influences = 0;
  int material = -1;
  bool hasTangents = false;
  // Where each source attribute is in `buffers` (-1: absent): the vertex array
  // reads them, and so does the skin cache (render/skin_cache.h).
  // `indices` are 32-bit, into the buffers' vertices: the full mesh's, then each
  // level's; `runIndices` the full mesh's again, 16-bit, each relative to its run's
  // first vertex, and what the vertex arrays bind.
  struct Sources {
    int positions = -1, normals = -1, uvs = -1, uvs1 = -1, colors = -1, joints = -1, weights = -1, tangents = -1,
        indices = -1, runIndices = -1;
  } sources;
  // An indexed triangle list's full mesh as runs (asset/vertex_runs.h): each
  // vertex of a run shaded once, where one draw of the whole list shades some
  // several times on llvmpipe. `sourceVertex` gives each buffer vertex's vertex in
  // PrimitiveData (empty: the same numbering).
  std::vector<VertexRun> runs;
  std::vector<std::uint32_t> sourceVertex;
  glm::vec3 center{0.0f};  // of the bind-pose bounds, mesh space: sorting BLEND draws
  // Morph targets: every displacement in one storage buffer, vertex-major, one
  // block per attribute that a target moves; each block's start (in vec4s, -1 for
  // none) as common/morph.glsl reads them.
  int morphTargets = 0;
  gl::Buffer morphDeltas;
  gl::Texture morphDeltaTexture;  // RGBA32F texels of morphDeltas
  int morphPositions = -1;
  int morphNormals = -1;
  int morphTangents = -1;
  // Coarser levels of detail (asset/mesh_lod.h), finest first, their indices after
  // the full mesh's in the same index buffer; empty unless uploaded with them.
  struct Level {
    GLsizei firstIndex = 0;
    GLsizei indexCount = 0;
    float error = 0.0f;  // MeshLod::error
    cull::ClusterRange clusters;  // its clusters in `clusters`
  };
  std::vector<Level> levels;
  // GPU culling (render/gpu_cull.h): an indexed triangle mesh's indices split into
  // runs of at most 128 triangles with their bounds (cull::appendClusters), the
  // full mesh's then each level's; empty for other primitives.
  std::vector<cull::Cluster> clusters;
  cull::ClusterRange fullClusters;
};

// Where one draw's glMultiDrawElementsIndirect commands lie in the bound
// GL_DRAW_INDIRECT_BUFFER (GPU culling's, render/gpu_cull.h).
struct IndirectDraw {
  GLintptr offset = 0;
  GLsizei count = 0;
};

// The level of detail drawn within `budget` (-1: the full mesh), as drawMesh picks it.
int levelIndexWithin(const GpuPrimitive& prim, float budget);
// One draw of `prim` from the bound vertex array (its own or a skin cache's): the
// level of detail `lodBudget` allows, the full mesh in its runs; or, with
// `indirect`, GPU culling's commands for it.
void drawMesh(const GpuPrimitive& prim, GLenum mode, float lodBudget, const IndirectDraw* indirect);
// Whether GPU culling can draw `prim` from its clusters: indexed triangles.
inline bool hasClusters(const GpuPrimitive& prim, int mode) { return mode == GL_TRIANGLES && !prim.clusters.empty(); }

struct UploadOptions {
  // Levels of detail to upload, [mesh][primitive] (ModelAsset::levelsOfDetail),
  // drawn where ModelFrame::lodBudget allows; none without.
  const std::vector<std::vector<std::vector<MeshLod>>>* levels = nullptr;
  // The model's material table as the scene layer made it (ModelAsset::materials);
  // null: made here from the model, by the same translation.
  const std::vector<SceneMaterial>* materials = nullptr;
};

class GpuModel {
 public:
  // Uploads every mesh and image of `model`. An image is uploaded as sRGB when a
  // material uses it for colour (base colour, emissive) and as linear data when
  // one uses it for normals, metallic-roughness or occlusion; both when both.
  static Result<GpuModel> upload(const ModelData& model, const UploadOptions& options = {});

  const std::vector<std::vector<GpuPrimitive>>& meshes() const { return meshes_; }
  // The texture of `image` in the wanted colour space, or a white one (no image).
  const gl::Texture& image(int image, bool srgb) const;
  // The sampler object of a glTF sampler's settings (one per distinct setting the
  // model's materials use; made on upload).
  const gl::Sampler& sampler(const SamplerData& settings) const;
  // KHR_materials_sheen's albedo table (core/sheen_table.h), uploaded only for a
  // model with a sheen.
  const gl::Texture& sheenAlbedo() const { return sheenAlbedo_; }
  // glTF material `material`'s entry of the scene layer's table (scene/materials.h),
  // or glTF's default material (-1): what its draws' uniforms and textures read.
  // Its images are referred to by index (image()); the model it was uploaded from
  // holds the decoded ones.
  const SceneMaterial& material(int material) const { return gltfMaterialOf(materials_, material); }

 private:
  std::vector<std::vector<GpuPrimitive>> meshes_;
  std::vector<SceneMaterial> materials_;
  std::vector<gl::Texture> srgbImages_;    // empty texture where no colour slot uses the image
  std::vector<gl::Texture> linearImages_;  // the same for data slots
  gl::Texture white_;
  std::map<SamplerData, gl::Sampler> samplers_;
  gl::Texture sheenAlbedo_;
};

// Whether a primitive with `influences` joints per vertex, drawn by `node`, is
// skinned in `mode` (SkinMode::None draws skins in their bind pose): the one rule
// the variants, the draws and the skin cache share.
inline bool skinnedBy(const NodeData& node, int influences, SkinMode mode) {
  return node.skin >= 0 && influences > 0 && mode != SkinMode::None;
}

// An LBS palette as common/skinning.glsl reads it: three texels a joint, the rows
// of its affine matrix (the fourth row of a skinning matrix is 0 0 0 1). A fourth
// texel a joint cost 16 fetches a vertex where 12 do.
inline void lbsPaletteRows(std::span<const glm::mat4> palette, std::vector<glm::vec4>& rows) {
  rows.resize(3 * palette.size());
  for (size_t j = 0; j < palette.size(); ++j) {
    const glm::mat4& m = palette[j];
    for (int r = 0; r < 3; ++r) rows[3 * j + size_t(r)] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
  }
}

// Sets `prim`'s attributes and indices on `vao`: its own buffers, or, with
// `deformed`, a skin cache's output for positions, normals and tangents (three
// vec4 per vertex, skin.comp's DeformedVertex) and no joints or weights.
void attachAttributes(const GpuPrimitive& prim, const gl::VertexArray& vao, const gl::Buffer* deformed);

// Binds `prim`'s morph displacements (storage buffer 1) and `weights` (storage
// buffer 2, floats; the drawn node's start at `first`) for a MORPH variant of
// `program`, with the uniforms common/morph.glsl reads.
void bindMorphTargets(const gl::Program& program, const GpuPrimitive& prim, const gl::Buffer& weights, int first);

}  // namespace engine
