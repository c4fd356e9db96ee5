#pragma once
// Draws a CDLOD selection: one grid of kPatchQuads^2 quads instanced once per patch,
// the height pages of the selected nodes in an R32F texture array (a fixed number
// of slots, reused least-recently-used first), and grass/rock/snow layers blended
// by height and slope, lit like every other mesh (common/lighting.glsl, fog, the
// same tone map as lit.frag).
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
#include "terrain/terrain.h"

namespace engine::terrain {

// GPU budget: height-page slots in the texture array, each kPageSide^2 floats
// (about 17.5 KiB): 2048 slots are 36 MiB. Fewer when the driver allows fewer layers.
inline constexpr int kGpuPageSlots = 2048;

struct TerrainDrawStats {
  std::size_t patchesDrawn = 0;
  std::size_t trianglesDrawn = 0;
  std::size_t pagesUploaded = 0;
  // Patches left out because one frame needed more pages than there are slots.
  std::size_t patchesSkipped = 0;
  float maxGeometricError = 0.0f;
};

class TerrainRenderer {
 public:
  // Sets whatever the caller's lighting needs on the terrain program: the uniforms
  // of lit.frag (u_sunDirection, u_sunColor, u_skyColor, u_groundColor,
  // u_fogColor, u_fogDensity), e.g. with render's setLightingUniforms.
  using UniformSetter = std::function<void(const gl::Program&)>;

  // Needs a current GL 4.5 context. `terrain` must outlive the renderer.
  // `defines` select shader variants (e.g. "SHADOWS" once the lead wires them).
  static Result<TerrainRenderer> create(const std::string& shaderDir, const Terrain& terrain,
                                        const std::vector<std::string>& defines = {});

  // Draws into the bound framebuffer with depth test on; `viewProjection` is the
  // camera-relative one the selection was made with.
  TerrainDrawStats draw(const LodSelection& selection, const glm::mat4& viewProjection,
                        const glm::dvec3& cameraPosition, const UniformSetter& setUniforms);

  const gl::Program& program() const { return program_; }
  int pageSlots() const { return slots_; }

 private:
  TerrainRenderer() = default;
  int residentSlot(const PageKey& key, std::size_t& uploads);

  const Terrain* terrain_ = nullptr;
  gl::Program program_;
  gl::Buffer vertices_, indices_, instances_;
  gl::VertexArray vertexArray_;
  gl::Object<gl::TextureDeleter> heightPages_;  // GL_TEXTURE_2D_ARRAY, R32F
  std::vector<gl::Texture> layers_;
  int slots_ = 0;
  std::uint64_t frame_ = 0;
  std::unordered_map<PageKey, int, PageKeyHash> slotOf_;
  std::vector<PageKey> slotKey_;
  std::vector<std::uint64_t> slotUsed_;  // frame of last use; 0 = free
};

}  // namespace engine::terrain
