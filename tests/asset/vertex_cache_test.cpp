// Triangle order for the vertex cache (asset/vertex_cache.h): the same triangles, each
// with its corners in the same order (so its facing is kept), fewer vertex shader
// runs on the models that ship and the samples, and blended or non-list primitives
// left in the order they are drawn in.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>

#include <meshoptimizer.h>

#include "../support/real_models.h"
#include "asset/gltf_loader.h"
#include "asset/vertex_cache.h"

namespace engine {
namespace {

// Each triangle as its three indices rotated to start at the smallest: the same
// triangle with the same winding compares equal, a flipped one does not.
std::vector<std::array<std::uint32_t, 3>> trianglesOf(const std::vector<std::uint32_t>& indices) {
  std::vector<std::array<std::uint32_t, 3>> out;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::array<std::uint32_t, 3> tri{indices[t], indices[t + 1], indices[t + 2]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Vertex shader runs per triangle through a 16-entry FIFO cache, a common model of a
// GPU's; llvmpipe's is different, but a better order is better for both.
float shadedPerTriangle(const std::vector<std::uint32_t>& indices, std::size_t vertices) {
  return meshopt_analyzeVertexCache(indices.data(), indices.size(), vertices, 16, 0, 0).acmr;
}

TEST(VertexCache, SameTrianglesFewerVertexRunsOnRealModels) {
  const int models = test::forEachReorderableList([](const std::string& path, const PrimitiveData& p) {
    const std::vector<std::uint32_t> ordered = orderForVertexCache(p.indices, p.positions.size());
    EXPECT_EQ(trianglesOf(ordered), trianglesOf(p.indices)) << path;
    const float before = shadedPerTriangle(p.indices, p.positions.size());
    const float after = shadedPerTriangle(ordered, p.positions.size());
    EXPECT_LE(after, before + 1e-6f) << path;
    std::printf("%s: %zu triangles, %.3f -> %.3f vertex runs a triangle\n",
                std::filesystem::path(path).filename().c_str(), p.indices.size() / 3, before, after);
  });
  EXPECT_GE(models, 2);
}

TEST(VertexCache, OnlyDepthTestedTriangleListsAreReordered) {
  ModelData model;
  model.materials.resize(2);
  model.materials[1].alphaMode = AlphaMode::Blend;
  PrimitiveData p;
  p.positions.resize(4);
  p.indices = {0, 1, 2, 2, 1, 3};
  EXPECT_TRUE(mayReorderTriangles(model, p));
  p.material = 1;
  EXPECT_FALSE(mayReorderTriangles(model, p)) << "blended: drawn in the file's order";
  p.material = 0;
  p.mode = 5;
  EXPECT_FALSE(mayReorderTriangles(model, p)) << "a strip's order is its shape";
  p.mode = 4;
  p.indices.pop_back();
  EXPECT_FALSE(mayReorderTriangles(model, p)) << "not whole triangles";
  p.indices.clear();
  EXPECT_FALSE(mayReorderTriangles(model, p)) << "not indexed";
}

}  // namespace
}  // namespace engine
