#include "asset/mesh_lod.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>
#include <meshoptimizer.h>

#include "core/closest_point.h"

namespace engine {
namespace {

// A level's triangles binned in a uniform grid over the mesh's bounds, each in
// every cell its box overlaps.
struct TriangleGrid {
  glm::vec3 lo{0.0f};
  float cell = 1.0f;
  glm::ivec3 cells{1};
  std::vector<std::vector<std::uint32_t>> bins;  // first index of each triangle

  TriangleGrid(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices, glm::vec3 low,
               glm::vec3 high) : lo(low) {
    const glm::vec3 size = glm::max(high - low, glm::vec3(1e-6f));
    // About one triangle a cell, over the box's volume.
    const float triangles = float(std::max<size_t>(indices.size() / 3, 1));
    cell = std::max(std::cbrt(size.x * size.y * size.z / triangles), std::max({size.x, size.y, size.z}) / 256.0f);
    cells = glm::clamp(glm::ivec3(glm::ceil(size / cell)), glm::ivec3(1), glm::ivec3(256));
    bins.resize(size_t(cells.x) * size_t(cells.y) * size_t(cells.z));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
      const glm::ivec3 from = cellOf(glm::min(a, glm::min(b, c))), to = cellOf(glm::max(a, glm::max(b, c)));
      for (int z = from.z; z <= to.z; ++z)
        for (int y = from.y; y <= to.y; ++y)
          for (int x = from.x; x <= to.x; ++x) bins[index({x, y, z})].push_back(std::uint32_t(t));
    }
  }
  glm::ivec3 cellOf(glm::vec3 p) const { return glm::clamp(glm::ivec3(glm::floor((p - lo) / cell)), glm::ivec3(0), cells - 1); }
  size_t index(glm::ivec3 c) const { return (size_t(c.z) * size_t(cells.y) + size_t(c.y)) * size_t(cells.x) + size_t(c.x); }
};

// The distance from p to the nearest triangle of the grid, searched in growing
// shells of cells; it stops once the nearest found is within `enough` (the caller
// needs no better) or nearer than any cell not searched yet can be.
float nearestDistance(const TriangleGrid& grid, const std::vector<glm::vec3>& positions,
                      const std::vector<std::uint32_t>& indices, glm::vec3 p, float enough) {
  const glm::ivec3 home = grid.cellOf(p);
  const int most = std::max({grid.cells.x, grid.cells.y, grid.cells.z});
  float best = std::numeric_limits<float>::infinity();
  for (int r = 0; r < most; ++r) {
    const glm::ivec3 from = glm::max(home - r, glm::ivec3(0)), to = glm::min(home + r, grid.cells - 1);
    for (int z = from.z; z <= to.z; ++z)
      for (int y = from.y; y <= to.y; ++y)
        for (int x = from.x; x <= to.x; ++x) {
          const glm::ivec3 c(x, y, z);
          const glm::ivec3 d = glm::abs(c - home);
          if (std::max({d.x, d.y, d.z}) != r) continue;  // searched in an earlier shell
          for (std::uint32_t t : grid.bins[grid.index(c)]) {
            const glm::vec3 q =
                closestOnTriangle(p, positions[indices[t]], positions[indices[t + 1]], positions[indices[t + 2]]);
            best = std::min(best, glm::length(p - q));
          }
        }
    // Every triangle not met yet lies in cells at least r + 1 shells away: at
    // least r cells from p, which is inside its own cell.
    if (best <= enough || best <= float(r) * grid.cell) break;
  }
  return best;
}

struct Box {
  glm::vec3 low, high;
};
Box boundsOf(const std::vector<glm::vec3>& positions) {
  Box b{positions[0], positions[0]};
  for (const glm::vec3& v : positions) {
    b.low = glm::min(b.low, v);
    b.high = glm::max(b.high, v);
  }
  return b;
}

// The farthest any vertex of the full mesh lies from `level`'s surface, exactly
// (vertices the level keeps are on it). `bounds`: the mesh's.
float farthestFromLevel(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& level,
                        const Box& bounds) {
  const TriangleGrid grid(positions, level, bounds.low, bounds.high);
  std::vector<bool> kept(positions.size(), false);
  for (std::uint32_t i : level) kept[i] = true;
  float worst = 0.0f;
  for (size_t v = 0; v < positions.size(); ++v) {
    if (kept[v]) continue;
    // Only a vertex farther than the worst so far can change the answer.
    worst = std::max(worst, nearestDistance(grid, positions, level, positions[v], worst));
  }
  return worst;
}

// The other way: the farthest a point of the level's triangles lies from the full
// mesh's surface (`full`: its triangles, `indices`, in a grid), where a coarse
// triangle bridges what the mesh left open (between an arm and the body). Sampled
// at the points of a 4 x 4 barycentric grid over each triangle (its corners are the
// mesh's own vertices, on its surface).
float farthestLevelPoint(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices,
                         const TriangleGrid& full, const std::vector<std::uint32_t>& level) {
  float worst = 0.0f;
  for (size_t t = 0; t + 2 < level.size(); t += 3)
    for (const glm::vec3& w : levelSamples()) {
      const glm::vec3 x = w.x * positions[level[t]] + w.y * positions[level[t + 1]] + w.z * positions[level[t + 2]];
      worst = std::max(worst, nearestDistance(full, positions, indices, x, worst));
    }
  return worst;
}

// Raises each level's error to its departure in one shape of the primitive, both
// ways, times `scale`; the full mesh's grid is made once for all the levels.
void measureIn(const std::vector<glm::vec3>& shape, const std::vector<std::uint32_t>& indices, float scale,
               std::vector<MeshLod>& levels) {
  const Box bounds = boundsOf(shape);
  const TriangleGrid full(shape, indices, bounds.low, bounds.high);
  for (MeshLod& level : levels) {
    const float departure = std::max(farthestFromLevel(shape, level.indices, bounds),
                                     farthestLevelPoint(shape, indices, full, level.indices));
    level.error = std::max(level.error, departure * scale);
  }
}

// Each vertex's normal from the full mesh's faces around it (area-weighted), for
// telling which way a surface faces whether or not the file has normals.
std::vector<glm::vec3> faceNormalsAtVertices(const PrimitiveData& p) {
  std::vector<glm::vec3> normals(p.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]], c = p.positions[p.indices[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) normals[p.indices[t + size_t(k)]] += n;
  }
  return normals;
}

// Whether some triangle of the level faces against the full mesh around its
// corners: the simplifier (0.18) can fold one over through a series of collapses
// (meshoptimizer issue 346), and a back-facing triangle is culled, which opens a
// hole where the full mesh has surface.
bool foldsOver(const PrimitiveData& p, const std::vector<glm::vec3>& vertexNormals,
               const std::vector<std::uint32_t>& level) {
  for (size_t t = 0; t + 2 < level.size(); t += 3) {
    const glm::vec3 a = p.positions[level[t]], b = p.positions[level[t + 1]], c = p.positions[level[t + 2]];
    const glm::vec3 around = vertexNormals[level[t]] + vertexNormals[level[t + 1]] + vertexNormals[level[t + 2]];
    if (glm::dot(glm::cross(b - a, c - a), around) < 0.0f) return true;
  }
  return false;
}

}  // namespace

const std::vector<glm::vec3>& levelSamples() {
  static const std::vector<glm::vec3> samples = [] {
    constexpr int kSteps = 4;
    std::vector<glm::vec3> out;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const int k = kSteps - i - j;
        if (i == kSteps || j == kSteps || k == kSteps) continue;  // the corners
        out.emplace_back(float(i) / kSteps, float(j) / kSteps, float(k) / kSteps);
      }
    return out;
  }();
  return samples;
}

std::vector<MeshLod> simplifiedLevels(const PrimitiveData& p, std::span<const std::vector<glm::vec3>> shapes,
                                      float scale, int minTriangles, float maxError) {
  std::vector<MeshLod> levels;
  if (p.mode != 4 || p.indices.size() < size_t(minTriangles) * 3 || p.positions.empty()) return levels;
  const std::span<const std::vector<glm::vec3>> own(&p.positions, 1);
  if (shapes.empty()) {
    const Box b = boundsOf(p.positions);
    shapes = own;
    scale = 1.0f / std::max({b.high.x - b.low.x, b.high.y - b.low.y, b.high.z - b.low.z, 1e-30f});
  }
  const std::vector<glm::vec3> vertexNormals = faceNormalsAtVertices(p);
  size_t previous = p.indices.size();
  for (;;) {
    MeshLod level;
    level.indices.resize(p.indices.size());  // the simplifier works in it: room for every index
    // Simplified from the full mesh each time (not from the previous level), so
    // that each level departs from the original surface by its own error only.
    float estimate = 0.0f;
    const size_t count = meshopt_simplify(level.indices.data(), p.indices.data(), p.indices.size(),
                                          &p.positions[0].x, p.positions.size(), sizeof(glm::vec3),
                                          previous / 2 / 3 * 3, maxError, 0, &estimate);
    if (count == 0 || count > previous * 4 / 5) break;
    level.indices.resize(count);
    if (foldsOver(p, vertexNormals, level.indices)) break;  // and coarser levels would too, or worse
    levels.push_back(std::move(level));
    previous = count;
    if (count < size_t(minTriangles) * 3 / 4) break;
  }
  // The simplifier's estimate (a quadric's: the distance to the planes of the
  // collapsed faces) understates the distance to the new surface, by 2-3.5x on the
  // tests' surfaces, and knows no pose; the error stated is measured instead.
  for (const std::vector<glm::vec3>& shape : shapes) measureIn(shape, p.indices, scale, levels);
  // Kept non-decreasing: a coarser level never claims to be closer.
  for (size_t i = 1; i < levels.size(); ++i) levels[i].error = std::max(levels[i].error, levels[i - 1].error);
  return levels;
}

}  // namespace engine
