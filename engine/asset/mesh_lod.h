#pragma once
// Levels of detail of a triangle mesh: coarser index lists over the same vertices
// (meshoptimizer's edge-collapse simplifier), so that skinning, morph targets and
// every attribute still apply unchanged and a level costs only its indices. GL-free.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "asset/model_data.h"

namespace engine {

struct MeshLod {
  std::vector<std::uint32_t> indices;
  // How far the level departs from the full mesh, measured when it is made, both
  // ways: the farthest vertex of the full mesh from the level's surface, and the
  // farthest of the level's points (levelSamples on each triangle) from the full
  // mesh's surface; the largest over the shapes it is measured in, times their
  // scale (simplifiedLevels).
  float error = 0.0f;
};

// Each level keeps about half the previous level's triangles (simplified on the
// primitive's own positions), stops when the simplifier cannot remove a fifth more
// without passing `maxError` (relative to the extent, its own estimate) or folds a
// triangle over (it would be culled: a hole), and is
// ordered finest first, with non-decreasing errors. The errors are measured in each
// of `shapes` (the primitive's positions posed: skinned, morphed, placed; a level
// that bridges an arm and the body is close in the rest pose and not in a stride),
// times `scale`; with no shapes, in its own positions relative to their extent
// (the bounding box's longest side). None for a primitive that is not indexed
// triangles or has fewer than `minTriangles`.
std::vector<MeshLod> simplifiedLevels(const PrimitiveData& primitive,
                                      std::span<const std::vector<glm::vec3>> shapes = {}, float scale = 0.0f,
                                      int minTriangles = 256, float maxError = 0.05f);

// The barycentric weights at which a level's triangles are sampled for its error:
// a 4 x 4 grid, corners left out.
const std::vector<glm::vec3>& levelSamples();

// The index of the coarsest of `levels` (finest first, each with an `error`:
// MeshLod, or a renderer's record of one) whose error is within `budget`, or -1 for
// the full mesh (a budget of 0 or less always gives -1).
template <typename Levels>
int coarsestWithin(const Levels& levels, float budget) {
  int chosen = -1;
  if (budget <= 0.0f) return chosen;
  for (const auto& level : levels) {
    if (level.error > budget) break;
    ++chosen;
  }
  return chosen;
}

}  // namespace engine
