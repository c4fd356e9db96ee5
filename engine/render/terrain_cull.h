#pragma once
// GPU culling of the terrain's CDLOD patches (render/gpu_cull.h): each patch's box,
// the cluster the cull tests it by. GL-free.
#include <cstdint>
#include <vector>

#include "render/cull_math.h"
#include "render/plane_occlusion.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"

namespace engine {

// The least and greatest height (metres above the terrain's origin) of the samples
// a patch's grid reads from its page (HeightPage::patchRanges), the heights
// terrain.vert's morph interpolates between: exact, where Terrain::regionBounds
// is a rigorous but loose bound (on a noise field it gives most patches the
// field's whole range).
terrain::HeightRange patchHeights(const terrain::Terrain& terrain, const terrain::LodPatch& patch);

// The box of a patch's vertices, camera-relative as terrain.vert places them:
// sample indices clamped to the field and taken relative to the camera's cell and
// fraction; heights within patchHeights. `indexCount` is the grid's (the
// cluster's draw).
cull::Cluster terrainPatchBox(const terrain::Terrain& terrain, const terrain::LodSelection& selection,
                              const terrain::LodPatch& patch, std::uint32_t indexCount);

// Removes the selection's patches that one of `quads` hides wholly
// (render/plane_occlusion.h); returns how many. The renderer does it for each view,
// and raster_floor for its floor, which draws what the renderer draws.
std::size_t removeHiddenPatches(const terrain::Terrain& terrain, terrain::LodSelection& selection,
                                const std::vector<cull::ScreenQuad>& quads, const glm::dmat4& viewProjection,
                                glm::dvec2 viewport, double pixelMargin = cull::kPlanePixelMargin);

}  // namespace engine
