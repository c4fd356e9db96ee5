#pragma once
// The terrain's triangles for a view, for every renderer: one CDLOD selection made
// from the view's eye, field of view and image height, the LOD target (the scene
// file's, or the renderer's override) and the height-page budget of the
// rasterizer's GPU pool. The rasterizer draws that selection (morphing on the GPU);
// the tracers take its triangles from terrainPatchMeshes, the CPU mirror of
// terrain.vert. Neither selects a terrain on its own, so a reference traced while
// the trade panel moves the LOD target traces the terrain the window draws.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "terrain/lod.h"

namespace engine {

namespace terrain {
class Terrain;
}

struct TerrainView {
  glm::dvec3 eye{0.0};
  double fovY = 1.0471975511965976;  // vertical, radians
  int viewportHeight = 720;
  double errorPixels = 2.0;  // the LOD target (terrainErrorTarget)
  std::size_t maxPages = SIZE_MAX;  // the height pages a selection may read
  // Camera-relative view-projection to cull against; none: every patch (a tracer's
  // terrain still casts shadows and reflects from outside the view).
  std::optional<glm::mat4> cullViewProjection;
  bool zeroToOneDepth = false;  // the cull matrix clips depth to 0..w (reverse-Z)
};

// The LOD target in pixels: `override` when above zero, else the scene file's.
double terrainErrorTarget(const SceneDesc& desc, double override);

// Measures the block errors the view's ranges need (terrain::measureBlocks); every
// selection from that eye then sees the same errors. Returns the blocks left.
std::size_t measureTerrain(const terrain::Terrain& field, const TerrainView& view);
// The patches to draw for the view, coarsened to fit view.maxPages.
terrain::LodSelection selectTerrain(const terrain::Terrain& field, const TerrainView& view);

// One patch's triangles in world space, with terrain.vert's layer uvs (relative to
// the view's eye, as the rasterizer computes them) and normals.
struct TerrainPatchMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
};
std::vector<TerrainPatchMesh> terrainPatchMeshes(const terrain::Terrain& field, const terrain::LodSelection& selection,
                                                 const glm::dvec3& eye);
// The triangle list every patch mesh shares (terrain::patchIndices).
const std::vector<std::uint32_t>& terrainPatchIndices();

}  // namespace engine
