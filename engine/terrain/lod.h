#pragma once
// Continuous distance-dependent level of detail (CDLOD, Strugar 2009). A quadtree
// of nodes over the field; each selected node is drawn as 2x2 patches of one fixed
// grid (kPatchQuads^2 quads) whose vertices morph toward the parent level's grid as
// their distance nears the end of the level's range, so levels meet without cracks
// and change without popping.
//
// Distances use the horizontal distance plus the camera's height above (or below)
// the terrain's whole height range: a function of a vertex's (x, z) alone, which
// makes a shared vertex morph identically in every patch that has it, and keeps the
// distance a lower bound of the true one, so the screen-space error stays under
// target. Ranges are then spaced so that (a) neighbours differ by at most one
// level, (b) a finer patch is fully morphed where it meets a coarser one and
// (c) the coarser one is not morphed there at all (see lod.cpp).
//
// The ranges depend on where the camera is: a level's mesh first shows where
// morphing toward it starts, so that distance is the farthest at which some block
// near the camera still has that mesh's own error (Terrain::meshError, measured per
// block by measureBlocks) projecting over target, not where the level-wide maximum,
// set by the roughest block of the whole field, would. They stay one per level, so
// the morph (and the shaders reading morphStart and morphEnd per level) is unchanged.
#include <array>
#include <cstdint>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "terrain/page_cache.h"
#include "terrain/terrain.h"

namespace engine::terrain {

// Morphing starts at this share of a level's range and ends just before it. The
// next level's error is held under target from the morph's start on, so the share
// trades only the morph's width against how far the finer level reaches: 0.8 draws
// 15% fewer triangles than 0.7 in micro_bench's table (4.0 M against 4.7 M at 1 px)
// and still spreads the morph over a fifth of the range.
inline constexpr double kMorphStartRatio = 0.8;
inline constexpr double kMorphEndRatio = 0.999;

struct LodCamera {
  glm::dvec3 position{0.0};
  // Camera-relative: the view has no translation (camera at the origin). Culling
  // uses the six planes of this matrix, whose depth range is GL's default -w..w
  // unless `zeroToOneDepth` (glClipControl's 0..w, as reverse-Z projections use).
  glm::mat4 viewProjection{1.0f};
  bool zeroToOneDepth = false;
  double fovY = 1.0471975511965976;  // vertical, radians
  int viewportHeight = 720;
  bool cull = true;
};

// Six planes (a, b, c, d): inside when a*x + b*y + c*z + d >= 0.
struct Frustum {
  std::array<glm::dvec4, 6> planes{};
  static Frustum fromViewProjection(const glm::mat4& viewProjection, bool zeroToOneDepth = false);
  // False only when the box is wholly outside one plane (conservative).
  bool intersects(const glm::dvec3& lo, const glm::dvec3& hi) const;
};

struct LodPatch {
  int level = 0;
  int gx = 0, gz = 0;  // global sample index of the patch's vertex (0, 0)
  PageKey node;        // the node (and height page) it belongs to
  // Metres: the largest distance of the level's mesh from full resolution over the
  // patch (Terrain::meshError), or of the next level's where it morphs, if larger.
  float error = 0.0f;
};

// The area a patch covers, as a node: a level-L patch is one level-(L-1) node; a
// level-0 patch lies in its own node (and has no error).
PageKey patchArea(const LodPatch& patch);

// Where the patch's vertex (0, 0) lies in its node's page, in the level's samples:
// (0 or kPatchQuads, 0 or kPatchQuads), as terrain.vert's `local` reads it.
inline glm::ivec2 patchPageOrigin(const LodPatch& patch) {
  const int s = Terrain::stride(patch.level);
  return {(patch.gx / s) % kNodeQuads, (patch.gz / s) % kNodeQuads};
}

struct LodStats {
  std::size_t patches = 0;
  std::size_t triangles = 0;
  float maxGeometricError = 0.0f;  // metres, over the drawn patches
  int finestLevel = 0;
  std::size_t pages = 0;     // distinct height pages (nodes) the patches read
  double targetPixels = 0;   // the error target the selection was made for
  int coarsenings = 0;       // times selectLodWithin raised the target to fit a page budget
  // Blocks near enough to set a range whose errors measureBlocks has not measured
  // yet: ranges rest on the level-wide estimate there, so once they are measured
  // the view's selection may be coarser, still within target.
  std::size_t blocksPending = 0;
};

struct LodSelection {
  std::vector<LodPatch> patches;
  // Per level: the selection range (metres) and the morph distances.
  std::array<double, kMaxLevels> range{};
  std::array<float, kMaxLevels> morphStart{}, morphEnd{};
  // The camera split for exact float maths: sample cell (integer) + fraction.
  glm::ivec2 cameraCell{0};
  glm::vec2 cameraFraction{0.0f};
  float cameraHeight = 0.0f;  // camera y - origin y
  float morphDy2 = 0.0f;      // squared height of the camera above/below the height range
  float spacing = 1.0f;
  glm::ivec2 cells{0};        // vertex indices are clamped to [0, cells]
  LodStats stats;
};

// Measures (Terrain::measureErrors), nearest first, up to `budget` (by default all)
// of the blocks that can set this camera's ranges at this target and are not
// measured yet, about 2 ms each on a noise field; returns how many are left. The
// ranges depend on the camera's position, field of view and viewport alone (not its
// direction or culling), so every selection from there sees the same errors until
// this is called again. A smaller budget spreads a new view's cost over frames, at
// the price of ranges (and images) that depend on the frames before.
std::size_t measureBlocks(const Terrain& terrain, const LodCamera& camera, double errorPixels,
                          std::size_t budget = SIZE_MAX);

// The patches to draw, with ranges from the blocks measured so far (elsewhere from
// the level-wide estimate, which keeps the finer levels out farther).
LodSelection selectLod(const Terrain& terrain, const LodCamera& camera, double errorPixels);

// Each step of selectLodWithin multiplies the error target by this.
inline constexpr double kCoarsenStep = 1.25;

// selectLod, but never needing more than `maxPages` height pages: while it would,
// the target is raised by kCoarsenStep and the selection made again (counted in
// stats.coarsenings; stats.targetPixels is the target used). If coarsening stops
// shrinking the page count first, the last selection is returned as it is and the
// caller sees stats.pages > maxPages.
LodSelection selectLodWithin(const Terrain& terrain, const LodCamera& camera, double errorPixels,
                             std::size_t maxPages);

// The CPU mirror of terrain.vert: morph factor of the vertex at global sample
// (gx, gz) of a level-`level` grid, and the camera-relative position of patch
// vertex (i, j) in [0, kPatchQuads]^2, with the same float operations in the same
// order as the shader.
float morphFactor(const LodSelection& selection, int level, int gx, int gz);
glm::vec3 patchVertex(const LodSelection& selection, const LodPatch& patch, const HeightPage& page,
                      int i, int j);
// All (kPatchQuads + 1)^2 vertices, row by row (j outer).
std::vector<glm::vec3> patchVertices(const Terrain& terrain, const LodSelection& selection,
                                     const LodPatch& patch);
// terrain.vert's v_normal of patch vertex (i, j): central differences of the page's
// heights at the level's stride, morphed toward the parent's like the position;
// and all of a patch's, in patchVertices' order.
glm::vec3 patchNormal(const LodSelection& selection, const LodPatch& patch, const HeightPage& page, int i, int j);
std::vector<glm::vec3> patchNormals(const Terrain& terrain, const LodSelection& selection, const LodPatch& patch);
// The triangles of that grid, as every renderer draws them (GPU, ray tracer, floor
// bench): each quad split along its (i, j)-(i+1, j+1) diagonal, the direction the
// morph and the error estimate assume; counter-clockwise seen from above.
std::vector<std::uint32_t> patchIndices();

}  // namespace engine::terrain
