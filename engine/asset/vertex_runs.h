#pragma once
// A triangle list cut into runs that llvmpipe shades each vertex of once. Its draw
// module takes an indexed draw of at most 4,096 16-bit indices, whose index range
// is known (glDrawRangeElementsBaseVertex) and starts at 0, as one range of
// vertices: each is fetched and shaded once, and the indices are used as they are.
// Any other indexed draw goes through a 256-entry direct-mapped cache of shaded
// vertices, keyed on the index's low bits, in segments of 1,024 indices: a vertex
// is looked up for every index and shaded again on every miss (CesiumMan: 3,722
// vertex shader runs for 3,273 vertices, in vertex cache order). Cut into runs of
// 1,365 triangles, each with its own copy of the vertices it uses, numbered from 0
// in the order it first uses them, CesiumMan is 3,402 vertices shaded once each,
// with no lookups. meshoptimizer's meshlets are the same idea, for at most 255
// vertices and 512 triangles (a GPU's mesh shader); llvmpipe wants runs 4,096
// indices long, so the cut here is our own, a few lines.
//
// GL-free: the renderer uploads the copies and the runs' 16-bit indices
// (render/model_renderer.h).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace engine {

// Indices a run: 1,365 whole triangles, within the draw module's 4,096.
inline constexpr std::uint32_t kRunIndices = 4095;

struct VertexRun {
  std::uint32_t firstIndex = 0;   // in the whole list's order, which runs keep
  std::uint32_t indexCount = 0;   // at most kRunIndices, whole triangles
  std::uint32_t firstVertex = 0;  // its vertices' first, in the split's numbering (base vertex)
  std::uint32_t vertexCount = 0;  // every one of them used by the run
};

struct RunSplit {
  // Vertex v of the split is a copy of source vertex sourceVertex[v].
  std::vector<std::uint32_t> sourceVertex;
  // The list's indices in their order, each relative to its run's firstVertex.
  std::vector<std::uint16_t> localIndices;
  std::vector<VertexRun> runs;
  // The split's index of each source vertex's first copy (~0u: unused), for index
  // lists that are not cut into runs (levels of detail) to draw the same vertices.
  std::vector<std::uint32_t> firstCopy;
};

// Cuts triangle list `indices` (over `sourceVertices` vertices) into runs of at
// most kRunIndices indices, in order.
RunSplit splitIntoRuns(std::span<const std::uint32_t> indices, std::size_t sourceVertices);

// The list as 32-bit indices into the split's copies (each run's first vertex plus
// its local index): what draws that are not in runs use (levels, indirect commands).
std::vector<std::uint32_t> indicesIntoCopies(const RunSplit& split);

// The runs' 16-bit indices as an index buffer holds them: padded by two, since Mesa's
// draw module shades a run as one range only where its draw ends before the buffer
// does (draw_pt_vsplit_tmp.h: end >= eltMax falls back to the cache).
std::vector<std::uint16_t> runIndexBuffer(const RunSplit& split);

// `values` (per source vertex, `perVertex` entries each) in the split's vertex order.
template <typename T>
std::vector<T> inSplitOrder(const std::vector<T>& values, const RunSplit& split, std::size_t perVertex = 1) {
  std::vector<T> out;
  if (values.empty()) return out;
  out.reserve(split.sourceVertex.size() * perVertex);
  for (const std::uint32_t v : split.sourceVertex)
    for (std::size_t k = 0; k < perVertex; ++k) out.push_back(values[v * perVertex + k]);
  return out;
}

}  // namespace engine
