#pragma once
// Triangle order for the post-transform vertex cache. A GPU, and Mesa's llvmpipe on
// the CPU, shade a vertex again whenever an index misses their small cache of vertices
// shaded lately; glTF files often list triangles in an order that misses it. Reordered
// with meshoptimizer's optimizeVertexCache, the same triangles need fewer vertex
// shader runs: measured on llvmpipe, 50 CesiumMan at 1280x720 went from 15.6 to 10.1
// ms of draw submission a frame (where llvmpipe shades vertices) and 30 to 23 ms a
// frame, the image unchanged byte for byte. The renderer now draws a full mesh in
// runs that llvmpipe shades each vertex of once (asset/vertex_runs.h); there the
// order keeps a run's triangles together, so that few vertices need a copy in two.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "asset/model_data.h"

namespace engine {

// The same triangles of a triangle list, reordered; `vertexCount` bounds the indices.
std::vector<std::uint32_t> orderForVertexCache(std::span<const std::uint32_t> indices, std::size_t vertexCount);

// Whether a primitive's triangles may be drawn in another order with the same image:
// an indexed triangle list whose material is not blended (blending composites its
// triangles in the order they are drawn; depth-tested ones do not care).
bool mayReorderTriangles(const ModelData& model, const PrimitiveData& primitive);

}  // namespace engine
