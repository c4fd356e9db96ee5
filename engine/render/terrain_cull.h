#pragma once
// GPU culling of the terrain's CDLOD patches (render/gpu_cull.h): each patch's box,
// the cluster the cull tests it by. GL-free.
#include <cstdint>

#include "render/cull_math.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"

namespace engine {

// The box of a patch's vertices, camera-relative as terrain.vert places them:
// sample indices clamped to the field and taken relative to the camera's cell and
// fraction; heights within the bounds of the patch's samples, which the morph only
// interpolates between. `indexCount` is the grid's (the cluster's draw).
cull::Cluster terrainPatchBox(const terrain::Terrain& terrain, const terrain::LodSelection& selection,
                              const terrain::LodPatch& patch, std::uint32_t indexCount);

}  // namespace engine
