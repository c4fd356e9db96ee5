#pragma once
// glTF models on the GPU: vertex buffers per primitive, textures per image, and
// the shader variants the model needs. A static mesh is drawn without skinning
// code; a skinned one with 4 or 8 influences, linear blend or dual quaternions;
// a mesh with morph targets with the morph code, before any skinning; each
// variant built only when first drawn.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/mesh_lod.h"
#include "asset/vertex_runs.h"
#include "render/cull_math.h"
#include "asset/model_data.h"
#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"

namespace engine {

// None draws skinned meshes in their bind pose with the static shader.
enum class SkinMode { Linear, DualQuat, None };

// One program of a vertex + fragment pair: each flag is a #define of the shaders
// (common/material.glsl lists the material ones), set only when a mesh needs it.
struct ShaderVariant {
  int influences = 0;  // 0 = static, 4 or 8
  SkinMode mode = SkinMode::Linear;
  bool textured = false;   // samples a base colour texture
  bool depthOnly = false;  // shadow passes
  bool normalMap = false;  // tangent-space normal map (the mesh has tangents)
  bool metallicRoughnessTexture = false;
  bool emissiveTexture = false;
  bool occlusion = false;  // occlusion texture
  bool alphaMask = false;  // alphaMode MASK: discard below the cutoff
  // Morph targets (common/morph.glsl), before skinning. Last, so that the
  // positional initialisations above keep their meaning.
  bool morph = false;
  // Some texture of the material reads TEXCOORD_1 or has a KHR_texture_transform
  // (common/material.glsl's UV_TRANSFORM); the others sample TEXCOORD_0 as it is.
  bool uvTransform = false;
  // KHR_materials_unlit (scene.frag's UNLIT): the base colour as it is. Last too.
  bool unlit = false;
  // The mesh's COLOR_0 multiplies the base colour (common/material.glsl's
  // VERTEX_COLOR); shadow passes read it only to cut out MASK holes.
  bool vertexColor = false;
  // KHR_materials_ior, _specular or _clearcoat away from their defaults: the layered
  // BRDF (common/shading.glsl's MATERIAL_LAYERS). Last as well.
  bool layers = false;
  bool layerTextures = false;  // some of them has a texture (LAYER_TEXTURES)
  // KHR_materials_transmission: refracts the opaque pass's image (scene.frag's
  // TRANSMISSION, common/transmission.glsl); drawn after the opaque pass.
  bool transmission = false;
  // KHR_materials_clearcoat's own normal map (CLEARCOAT_NORMAL), on a mesh with
  // tangents.
  bool clearcoatNormal = false;
  // KHR_materials_sheen (SHEEN): a sheen lobe over the base, dimmed by the sheen's
  // albedo table (GpuModel::sheenAlbedo).
  bool sheen = false;
  // KHR_materials_anisotropy (ANISOTROPY), on a mesh with tangents: the base's
  // highlight stretched along a direction of the tangent frame.
  bool anisotropy = false;
  // KHR_materials_iridescence (IRIDESCENCE): the thin film's Fresnel.
  bool iridescence = false;
  // Classic shading of a material without a highlight (specular 0: CLASSIC_MATTE,
  // common/shading.glsl). ShaderVariants drops it where its shaders are not classic.
  bool matte = false;
  // A draw lying wholly where the sun's near map covers fully (render/sun_coverage.h's
  // withinNearSunMap): the far map's lookups left out (SUN_FAR_SHADOWS), which
  // shadows.glsl weighs by zero there: the same bytes. ShaderVariants drops it where
  // its programs have no far map.
  bool nearSunOnly = false;
  // Back faces culled (every colour pass culls them; the material is not
  // double-sided): gl_FrontFacing is always true, so scene.frag's flip of a back
  // face's normal is left out (ONE_SIDED): the same bytes, and no work a fragment
  // for a flip that never happens. ShaderVariants drops it from depth-only programs.
  bool oneSided = false;
  // The deferred characters (render/character_surface_pass.h):
  // the surface pass writes common/surface.glsl's targets instead of a colour
  // (SURFACE_OUT); the shading pass reads them back, a full-screen triangle
  // (SURFACE_IN, sky.vert's vertices), and lights each pixel once.
  enum class Surface : std::uint8_t { None, Out, In };
  Surface surface = Surface::None;
  auto operator<=>(const ShaderVariant&) const = default;
  std::string describe() const;
  // Whether a surface holds all this variant's fragments read: the base colour is
  // the only texture (its level of detail is the surface's one), no fragment is
  // discarded, blended or refracting, and nothing is interpolated but the
  // position, the normal and TEXCOORD_0.
  bool deferrable() const;
  // The full-screen variant that shades what this one's surface pass left: the
  // vertex stage's flags dropped, so meshes of one material share it.
  ShaderVariant shadingFromSurface() const;
};

// Builds and caches the scene programs by variant, each only when first asked for:
// scene.vert + scene.frag (depth.frag for depth-only variants, sky.vert's
// full-screen triangle for SURFACE_IN), as the scene renderer draws every mesh with
// them. Without `defines` (tests) the lights' counts come from the frame block
// (common/direct_light.glsl); whatever draws with these programs binds that block
// (render/frame_block.h) and culls back faces in its colour passes, as the scene
// renderer does (ShaderVariant::oneSided).
class ShaderVariants {
 public:
  explicit ShaderVariants(std::string shaderDir, std::vector<std::string> defines = {})
      : shaderDir_(std::move(shaderDir)),
        defines_(std::move(defines)),
        classic_(std::find(defines_.begin(), defines_.end(), "CLASSIC 1") != defines_.end()),
        farSun_(std::find(defines_.begin(), defines_.end(), kFarSunDefine) != defines_.end()) {}
  // `feedback` names varyings to capture with transform feedback (tests).
  Result<const gl::Program*> get(const ShaderVariant& variant,
                                 const std::vector<std::string>& feedback = {});
  std::vector<ShaderVariant> built() const;

 private:
  Result<gl::Program> build(const ShaderVariant& variant, const std::vector<std::string>& feedback) const;

  std::string shaderDir_;
  std::vector<std::string> defines_;  // for every variant (shading model, shadows, fog)
  static constexpr const char* kFarSunDefine = "SUN_FAR_SHADOWS 1";
  bool classic_;                      // defines_ has CLASSIC: ShaderVariant::matte applies
  bool farSun_;                       // defines_ has SUN_FAR_SHADOWS: ShaderVariant::nearSunOnly applies
  std::map<ShaderVariant, gl::Program> programs_;
  std::map<std::pair<ShaderVariant, std::vector<std::string>>, gl::Program> feedbackPrograms_;
};

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

 private:
  std::vector<std::vector<GpuPrimitive>> meshes_;
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

// The variant a primitive of `node` is drawn with (skinning mode, material
// textures, alpha mask), for a colour pass or, with `depthOnly`, a shadow pass.
// With `cached`, the primitive is drawn from a skin cache (render/skin_cache.h),
// already deformed: no skinning or morph code.
ShaderVariant primitiveVariant(const ModelData& model, const NodeData& node, const PrimitiveData& prim,
                               SkinMode mode, bool depthOnly, bool cached = false);

// Sets `prim`'s attributes and indices on `vao`: its own buffers, or, with
// `deformed`, a skin cache's output for positions, normals and tangents (three
// vec4 per vertex, skin.comp's DeformedVertex) and no joints or weights.
void attachAttributes(const GpuPrimitive& prim, const gl::VertexArray& vao, const gl::Buffer* deformed);

// Binds `prim`'s morph displacements (storage buffer 1) and `weights` (storage
// buffer 2, floats; the drawn node's start at `first`) for a MORPH variant of
// `program`, with the uniforms common/morph.glsl reads.
void bindMorphTargets(const gl::Program& program, const GpuPrimitive& prim, const gl::Buffer& weights, int first);

// One frame's inputs for drawing a model.
struct ModelFrame {
  glm::mat4 viewProjection{1.0f};
  glm::dvec3 cameraPosition{0.0};
  // World matrix of every glTF node (node order).
  std::span<const glm::mat4> nodeWorlds;
  // The model's root in the world: skinned primitives are placed by it, their
  // palettes being in the root's space (model space).
  glm::dmat4 root{1.0};
  // One RGBA32F buffer texture per skin: a mat4 palette (Linear, four texels a
  // joint) or 2 vec4 per joint (DualQuat).
  std::span<const gl::Texture> skinPalettes;
  SkinMode skinMode = SkinMode::Linear;
  // Models with morph targets: every morphing node's weights in one storage buffer
  // (float, MorphLayout order) and where each node's start (per glTF node, -1 none).
  const gl::Buffer* morphWeights = nullptr;
  std::span<const int> morphFirst;
  // The instance's skin cache, when it has one: its deforming primitives are
  // drawn from it as static meshes (placed as before: skinned ones by the root).
  const class SkinCache* skinCache = nullptr;
  // Sets what the program needs besides the mesh and material (lights, shadows).
  std::function<void(const gl::Program&)> setUniforms;
  bool depthOnly = false;  // shadow passes: no material, depth-only variant
  bool nearSunOnly = false;  // ShaderVariant::nearSunOnly for every primitive drawn
  // ShaderVariant::surface for every primitive drawn (the deferred characters'
  // surface pass: Out).
  ShaderVariant::Surface surface = ShaderVariant::Surface::None;
  // The largest error a level of detail may have, as MeshLod::error states it (the
  // coarsest level within it is drawn); 0: every mesh in full.
  float lodBudget = 0.0f;
  // Whether drawModel also draws the BLEND primitives (after the others, back to
  // front, blending on). A scene turns it off and sorts them across all models.
  bool includeBlend = true;
  // GPU culling: the commands of each instance of the one primitive drawn
  // (drawModelPrimitive), in primitiveInstanceModels' order; empty: plain draws.
  std::span<const IndirectDraw> indirect;
};

// The u_model of every instance drawPrimitive draws of node `node`'s primitives
// (EXT_mesh_gpu_instancing's instances, or the node once): what GPU culling
// transforms their clusters by, bit for bit.
std::vector<glm::mat4> primitiveInstanceModels(const ModelData& model, const ModelFrame& frame, int node, int influences);

// A BLEND primitive of a model and its distance from the camera (the centre of
// its bounds), for sorting back to front.
struct BlendPrimitive {
  int node = -1;
  int primitive = -1;
  double distance = 0.0;
};

// The model's BLEND primitives with their distances; `nodeWorlds` are
// camera-relative (the camera at the origin).
std::vector<BlendPrimitive> blendPrimitives(const ModelData& model, const GpuModel& gpu,
                                            std::span<const glm::mat4> nodeWorlds);

// Draws every opaque and MASK (node, primitive) instance of the model, then, when
// frame.includeBlend and not frame.depthOnly, the BLEND ones back to front.
// BLEND materials cast no shadow: a tinted glass pane in a depth map would be an
// opaque sheet.
Status drawModel(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                 const ModelFrame& frame);
// Draws primitive `primitive` of `node` with the blend and depth state the caller
// set (a pass's: render/pass_state.h); only a double-sided material's culling is
// changed, and put back.
Status drawModelPrimitive(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                          const ModelFrame& frame, int node, int primitive);
// The deferred characters' shading of material `material` of `model` (-1: glTF's
// default): one full-screen triangle with the program of `shading`
// (ShaderVariant::shadingFromSurface of its surface pass), over the pixels that the
// caller's stencil test lets through. `setUniforms` as ModelFrame's.
Status shadeModelSurface(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu, int material,
                         const ShaderVariant& shading, const std::function<void(const gl::Program&)>& setUniforms,
                         const glm::mat4& inverseViewProjection);
// Draws one BLEND primitive, with the blend state set around it (blending in
// the target's linear colour, depth test on, depth writes off).
Status drawBlendPrimitive(ShaderVariants& variants, const ModelData& model, const GpuModel& gpu,
                          const ModelFrame& frame, const BlendPrimitive& primitive);

}  // namespace engine
