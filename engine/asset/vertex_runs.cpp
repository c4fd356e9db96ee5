#include "asset/vertex_runs.h"

#include <algorithm>

namespace engine {

namespace {

constexpr std::uint32_t kUnused = ~0u;

// Appends the run of indices [first, first + count) to `split`. `slot` maps source
// vertices to this run's local numbers and is left as it was found (all kUnused).
void appendRun(std::span<const std::uint32_t> indices, std::uint32_t first, std::uint32_t count, RunSplit& split,
               std::vector<std::uint32_t>& slot) {
  VertexRun run{first, count, std::uint32_t(split.sourceVertex.size()), 0};
  for (std::uint32_t i = first; i < first + count; ++i) {
    const std::uint32_t v = indices[i];
    if (slot[v] == kUnused) {
      slot[v] = run.vertexCount++;
      if (split.firstCopy[v] == kUnused) split.firstCopy[v] = std::uint32_t(split.sourceVertex.size());
      split.sourceVertex.push_back(v);
    }
    split.localIndices.push_back(std::uint16_t(slot[v]));
  }
  for (std::uint32_t k = run.firstVertex; k < run.firstVertex + run.vertexCount; ++k) slot[split.sourceVertex[k]] = kUnused;
  split.runs.push_back(run);
}

}  // namespace

RunSplit splitIntoRuns(std::span<const std::uint32_t> indices, std::size_t sourceVertices) {
  RunSplit split;
  split.firstCopy.assign(sourceVertices, kUnused);
  split.localIndices.reserve(indices.size());
  std::vector<std::uint32_t> slot(sourceVertices, kUnused);
  const std::uint32_t total = std::uint32_t(indices.size());
  for (std::uint32_t first = 0; first < total; first += kRunIndices)
    appendRun(indices, first, std::min(kRunIndices, total - first), split, slot);
  return split;
}

std::vector<std::uint32_t> indicesIntoCopies(const RunSplit& split) {
  std::vector<std::uint32_t> out;
  out.reserve(split.localIndices.size());
  for (const VertexRun& run : split.runs)
    for (std::uint32_t i = run.firstIndex; i < run.firstIndex + run.indexCount; ++i)
      out.push_back(run.firstVertex + split.localIndices[i]);
  return out;
}

std::vector<std::uint16_t> runIndexBuffer(const RunSplit& split) {
  std::vector<std::uint16_t> out = split.localIndices;
  out.resize(out.size() + 2, 0);
  return out;
}

}  // namespace engine
