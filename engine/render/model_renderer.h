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
#include "render/gpu_model.h"
#include "scene/materials.h"

namespace engine {

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


// The variant a primitive of `node` is drawn with (skinning mode, material
// textures, alpha mask), for a colour pass or, with `depthOnly`, a shadow pass.
// With `cached`, the primitive is drawn from a skin cache (render/skin_cache.h),
// already deformed: no skinning or morph code.
ShaderVariant primitiveVariant(const ModelData& model, const NodeData& node, const PrimitiveData& prim,
                               SkinMode mode, bool depthOnly, bool cached = false);

// One frame's inputs for drawing a model.
struct ModelFrame {
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
