#pragma once
// Levels of detail of a triangle mesh: coarser index lists over the same vertices
// (meshoptimizer's edge-collapse simplifier), so that skinning, morph targets and
// every attribute still apply unchanged and a level costs only its indices. GL-free.
#include <cstdint>
#include <vector>

#include "asset/model_data.h"

namespace engine {

struct MeshLod {
  std::vector<std::uint32_t> indices;
  // The largest distance from a vertex of the full mesh to this level's surface
  // (measured when the level is made), relative to the mesh's extent (its bounding
  // box's longest side): multiply by the mesh's size on screen to get pixels.
  float error = 0.0f;
};

// Each level keeps about half the previous level's triangles, stops when the
// simplifier cannot remove a fifth more without passing `maxError` (relative, its
// own estimate),
// and is ordered finest first, with non-decreasing errors. None for a primitive
// that is not indexed triangles or has fewer than `minTriangles`.
std::vector<MeshLod> simplifiedLevels(const PrimitiveData& primitive, int minTriangles = 256, float maxError = 0.05f);

// The coarsest of `levels` whose error is within `budget` (relative), or -1 for
// the full mesh (a budget of 0 or less always gives -1).
int coarsestWithin(const std::vector<float>& errors, float budget);

}  // namespace engine
