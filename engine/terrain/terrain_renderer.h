#pragma once
// Draws a CDLOD selection: one grid of kPatchQuads^2 quads instanced once per patch,
// the height pages of the selected nodes in an R32F texture-array atlas (a pool of
// page slots sized from a GPU byte budget, filled per draw with only the pages the
// selection reads, least recently used evicted first), and grass/rock/snow layers
// blended by height and slope. Shaded like every scene mesh: the frame block
// (common/frame.glsl, bound at binding 0 by the caller), common/shading.glsl, the
// sun and point shadows and fog, into an HDR target.
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "terrain/lod.h"
#include "terrain/page_pool.h"
#include "terrain/terrain.h"

namespace engine::terrain {


// What the colour draws write: the shaded colour, or (after enableDeferred) the
// surface terrain_deferred.frag shades later, once a pixel.
enum class TerrainOutput { Colour, Surface };

struct TerrainDrawStats {
  std::size_t patchesDrawn = 0;
  std::size_t trianglesDrawn = 0;
  std::size_t pagesUploaded = 0;
  // Patches left out because one draw needed more pages than there are slots.
  // Zero whenever the selection came from selectLodWithin(..., pageSlots()).
  std::size_t patchesSkipped = 0;
  float maxGeometricError = 0.0f;
};

class TerrainRenderer {
 public:
  // Sets whatever else the caller's lighting needs on the colour program (shadow
  // map bindings and u_sunTexelWorld, u_pointNear, as for scene programs).
  using UniformSetter = std::function<void(const gl::Program&)>;

  // Needs a current GL 4.5 context. `terrain` must outlive the renderer.
  // `defines` select the colour program's variant, the scene programs' own
  // (CLASSIC, SUN_SHADOWS, POINT_SHADOWS, FOG). `gpuBudgetBytes` sizes the page
  // pool (at least kMinGpuPageSlots slots, at most what the driver's layer limit allows).
  static Result<TerrainRenderer> create(const std::string& shaderDir, const Terrain& terrain,
                                        const std::vector<std::string>& defines = {},
                                        std::size_t gpuBudgetBytes = kDefaultGpuPageBudgetBytes);

  // Draws into the bound framebuffer with depth test on. The frame block must be
  // bound, its view-projection the camera-relative one the selection was made with.
  TerrainDrawStats draw(const LodSelection& selection, const glm::dvec3& cameraPosition,
                        const UniformSetter& setUniforms, TerrainOutput output = TerrainOutput::Colour);
  // Shading once a pixel (llvmpipe shades eight lanes at a time, and far patches'
  // triangles cover a pixel or two each): enableDeferred builds the two programs
  // (`defines` as create's); draws with TerrainOutput::Surface then write into the
  // bound framebuffer's one colour output the surface terrain_deferred.frag reads
  // (RGBA32F: distance, normal, texture level); shadeDeferred shades every pixel
  // the caller's stencil test lets through from that surface, bound by the setter
  // at gl::binding::kTerrainSurface, `inverseViewProjection` the view's
  // (camera-relative world).
  Status enableDeferred(const std::string& shaderDir, const std::vector<std::string>& defines);
  void shadeDeferred(const LodSelection& selection, const glm::dvec3& cameraPosition,
                     const glm::mat4& inverseViewProjection, const UniformSetter& setUniforms) const;

  // Depth only, through `lightViewProjection` (camera-relative world -> clip), for
  // a shadow map.
  TerrainDrawStats drawDepth(const LodSelection& selection, const glm::mat4& lightViewProjection);

  // GPU culling (render/gpu_cull.h) draws the colour pass in parts, from indirect
  // commands: prepare makes the selection's pages resident and fills the instance
  // buffer once (patches() is then the instances in order); drawIndirect draws
  // `count` commands from byte `offset` of the bound GL_DRAW_INDIRECT_BUFFER, each
  // a run of those instances (baseInstance), with draw's program and uniforms.
  TerrainDrawStats prepare(const LodSelection& selection) { return upload(selection); }
  const std::vector<LodPatch>& patches() const { return drawnPatches_; }
  void drawIndirect(const LodSelection& selection, const glm::dvec3& cameraPosition, const UniformSetter& setUniforms,
                    std::intptr_t offset, int count, TerrainOutput output = TerrainOutput::Colour) const;
  // The grid's indices a patch draws (GL_UNSIGNED_SHORT).
  static int indexCount();

  const gl::Program& program() const { return program_; }
  int pageSlots() const { return slots_; }
  int pagesResident() const { return int(slotOf_.size()); }
  // Bytes this renderer holds on the GPU: page atlas, instance buffer, grid, layers.
  std::size_t gpuBytes() const;

 private:
  TerrainRenderer() = default;
  TerrainDrawStats upload(const LodSelection& selection);
  void assignSlots(const std::vector<PageKey>& missing, std::size_t& uploads);
  void setGridUniforms(const gl::Program& p, const LodSelection& selection) const;
  void drawInstances(std::size_t count) const;
  void useColourProgram(const LodSelection& selection, const glm::dvec3& cameraPosition,
                        const UniformSetter& setUniforms, TerrainOutput output) const {
    const gl::Program& p = output == TerrainOutput::Surface ? surfaceProgram_ : program_;
    setGridUniforms(p, selection);
    useShadingProgram(p, selection, cameraPosition, output == TerrainOutput::Surface ? nullptr : setUniforms);
  }
  // The layers' uniforms and textures, for terrain.vert's programs and the deferred
  // shading pass's full-screen one (which has no grid).
  void useShadingProgram(const gl::Program& p, const LodSelection& selection, const glm::dvec3& cameraPosition,
                         const UniformSetter& setUniforms) const;

  const Terrain* terrain_ = nullptr;
  gl::Program program_, depthProgram_;
  gl::Program surfaceProgram_, deferredProgram_;  // only after enableDeferred
  gl::VertexArray emptyVertexArray_;
  gl::Buffer vertices_, indices_, instances_;
  gl::VertexArray vertexArray_;
  gl::Object<gl::TextureDeleter> heightPages_;  // GL_TEXTURE_2D_ARRAY, R32F atlas
  std::vector<gl::Texture> layers_;
  std::size_t layerBytes_ = 0;
  int slots_ = 0, atlasLayers_ = 0;
  std::uint64_t frame_ = 0;
  std::unordered_map<PageKey, int, PageKeyHash> slotOf_;
  std::vector<PageKey> slotKey_;
  std::vector<std::uint64_t> slotUsed_;  // draw of last use; 0 = free
  std::vector<LodPatch> drawnPatches_;   // the last upload's instances, in order
};

}  // namespace engine::terrain
