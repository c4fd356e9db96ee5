// Triangle lists cut into runs (asset/vertex_runs.h): every run within the draw
// module's limit, of whole triangles, each vertex of a run used by it (llvmpipe
// shades the run's whole range), and the copies drawing the very same triangles,
// corner for corner, over many random lists and the shipped models.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "../support/real_models.h"
#include "asset/vertex_runs.h"

namespace engine {
namespace {

// Checks everything splitIntoRuns promises of `split`, made from `indices` over
// `vertices` source vertices.
void expectValidSplit(const std::vector<std::uint32_t>& indices, std::size_t vertices, const RunSplit& split) {
  ASSERT_EQ(split.localIndices.size(), indices.size());
  ASSERT_EQ(split.firstCopy.size(), vertices);
  std::uint32_t nextIndex = 0, nextVertex = 0;
  for (const VertexRun& run : split.runs) {
    // In order, back to back, whole triangles within the limit.
    ASSERT_EQ(run.firstIndex, nextIndex);
    ASSERT_EQ(run.firstVertex, nextVertex);
    ASSERT_GT(run.indexCount, 0u);
    ASSERT_LE(run.indexCount, kRunIndices);
    ASSERT_EQ(run.indexCount % 3, 0u);
    std::vector<char> used(run.vertexCount, 0);
    for (std::uint32_t i = run.firstIndex; i < run.firstIndex + run.indexCount; ++i) {
      const std::uint32_t local = split.localIndices[i];
      ASSERT_LT(local, run.vertexCount) << "index " << i;
      used[local] = 1;
      // The copy is of the vertex the list names.
      ASSERT_EQ(split.sourceVertex[run.firstVertex + local], indices[i]) << "index " << i;
    }
    for (std::uint32_t v = 0; v < run.vertexCount; ++v) ASSERT_TRUE(used[v]) << "unused vertex " << v << " of a run";
    nextIndex += run.indexCount;
    nextVertex += run.vertexCount;
  }
  EXPECT_EQ(nextIndex, indices.size());
  EXPECT_EQ(nextVertex, split.sourceVertex.size());
  // As few runs as the limit allows.
  EXPECT_EQ(split.runs.size(), (indices.size() + kRunIndices - 1) / kRunIndices);
  // A first copy for every vertex used, none for the others.
  std::vector<char> usedSource(vertices, 0);
  for (const std::uint32_t v : indices) usedSource[v] = 1;
  for (std::size_t v = 0; v < vertices; ++v) {
    if (!usedSource[v]) {
      EXPECT_EQ(split.firstCopy[v], ~0u) << "vertex " << v;
      continue;
    }
    ASSERT_LT(split.firstCopy[v], split.sourceVertex.size());
    EXPECT_EQ(split.sourceVertex[split.firstCopy[v]], v);
  }
}

TEST(VertexRuns, RandomListsOfEverySizeAroundTheLimit) {
  std::mt19937 rng(14);
  int lists = 0;
  // Lengths at and either side of one, two and several runs, and random ones; few
  // vertices (every run uses most of them) and many (most used once).
  std::vector<std::size_t> triangles = {0, 1, 2, kRunIndices / 3 - 1, kRunIndices / 3, kRunIndices / 3 + 1,
                                        2 * kRunIndices / 3, 2 * kRunIndices / 3 + 1, 5 * kRunIndices / 3 + 7};
  for (int i = 0; i < 200; ++i) triangles.push_back(std::uniform_int_distribution<std::size_t>(0, 12000)(rng));
  for (const std::size_t count : triangles) {
    for (const std::size_t vertices : {std::size_t(3), std::size_t(50), std::size_t(5000), std::size_t(70000)}) {
      std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices - 1));
      std::vector<std::uint32_t> indices(count * 3);
      for (std::uint32_t& index : indices) index = vertex(rng);
      const RunSplit split = splitIntoRuns(indices, vertices);
      expectValidSplit(indices, vertices, split);
      if (HasFatalFailure()) return;
      ++lists;
    }
  }
  EXPECT_EQ(lists, int(triangles.size()) * 4);
}

TEST(VertexRuns, AttributesFollowTheirVertices) {
  const std::vector<std::uint32_t> indices = {4, 1, 2, 2, 1, 4};
  const RunSplit split = splitIntoRuns(indices, 5);
  ASSERT_EQ(split.sourceVertex, (std::vector<std::uint32_t>{4, 1, 2}));
  const std::vector<float> pairs = {0, 1, 10, 11, 20, 21, 30, 31, 40, 41};  // two a vertex
  EXPECT_EQ(inSplitOrder(pairs, split, 2), (std::vector<float>{40, 41, 10, 11, 20, 21}));
  EXPECT_TRUE(inSplitOrder(std::vector<float>{}, split).empty());
}

// The shipped and sample models in vertex cache order, as the renderer cuts them:
// few copies (what the runs cost in memory and in shading at their edges).
TEST(VertexRuns, RealModelsCopyFewVertices) {
  const int models = test::forEachReorderableList([](const std::string& path, const PrimitiveData& p) {
    const std::vector<std::uint32_t> ordered = orderForVertexCache(p.indices, p.positions.size());
    const RunSplit split = splitIntoRuns(ordered, p.positions.size());
    expectValidSplit(ordered, p.positions.size(), split);
    const double copies = double(split.sourceVertex.size()) / double(p.positions.size());
    std::printf("%s: %zu vertices, %zu in %zu runs (%.3fx)\n", std::filesystem::path(path).filename().c_str(),
                p.positions.size(), split.sourceVertex.size(), split.runs.size(), copies);
    // CesiumMan: 1.04x. A run of 1,365 triangles shares its edge with the next.
    EXPECT_LE(copies, 1.15) << path;
  });
  EXPECT_GE(models, 1);
}

}  // namespace
}  // namespace engine
