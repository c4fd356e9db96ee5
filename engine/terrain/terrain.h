#pragma once
// A height field over a square grid of samples, from a PNG or from seeded noise,
// placed in the world by an origin in double precision. Heights are read through a
// page cache with a byte budget, so a 16 km field at 1 m spacing (over 1 GB as
// floats) never needs to be in memory whole: pages are made on demand and the
// least recently used ones are dropped.
//
// Sample (ix, iz) sits at world origin + (ix * spacing, h, iz * spacing); a PNG's
// columns run along +x and its rows along +z.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "terrain/height_source.h"
#include "terrain/page_cache.h"

namespace engine::terrain {

// Beyond this many cells a side, sample indices and the float maths of the vertex
// shader (exact integers below 2^24 after the camera offset) are no longer safe.
inline constexpr int kMaxCellsPerSide = 65536;
inline constexpr int kMaxLevels = 16;
// Levels whose error Terrain::meshError can give per node, measured exactly;
// coarser ones have only the level-wide estimate. A level-L node is 4^(L-1)
// blocks (level-1 nodes) to measure, each a scan of its 129^2 samples.
inline constexpr int kExactErrorLevels = 2;

struct TerrainSettings {
  std::string heightmap;        // PNG (8 or 16 bit); empty: procedural noise
  std::uint32_t seed = 1;       // procedural only
  double size = 4096.0;         // metres along the larger side
  double spacing = 1.0;         // metres between samples (procedural; a PNG's follows from size)
  double heightScale = 400.0;   // metres from black (or noise minimum) to white
  glm::dvec3 origin{0.0};       // world position of sample (0, 0) at height 0
  double featureSize = 0.0;     // metres, widest noise feature; 0: a quarter of `size`
  int octaves = 12;             // procedural noise octaves (finer than 2 samples are dropped)
  std::size_t pageCacheBytes = kDefaultPageCacheBytes;
};

class Terrain {
 public:
  // Errors name the heightmap file or the settings field at fault.
  static Result<Terrain> create(const TerrainSettings& settings);

  // World height and normal at world (x, z): bilinear between the four samples
  // around it, clamped to the edge outside the field. Not thread-safe (pages may
  // be made and evicted).
  double heightAt(double x, double z) const;
  glm::vec3 normalAt(double x, double z) const;

  const glm::dvec3& origin() const { return origin_; }
  double spacing() const { return spacing_; }
  int cellsX() const { return cellsX_; }
  int cellsZ() const { return cellsZ_; }
  // Quadtree levels: 0 is full resolution, levelCount() - 1 the single root node.
  int levelCount() const { return levelCount_; }
  // Samples between vertices of a level's grid, and the node's side in metres.
  static int stride(int level) { return 1 << level; }
  double nodeSize(int level) const { return double(kNodeQuads) * stride(level) * spacing_; }
  // Largest vertical distance (metres) between the level's mesh and the
  // full-resolution mesh: exact for a PNG, estimated from probes with a safety
  // factor for noise (see terrain.cpp).
  float geometricError(int level) const { return errors_[std::size_t(level)]; }
  // The level-`level` mesh's largest vertical distance from the full-resolution one
  // over a node's area (a node of that level or a finer one), for the
  // view-dependent ranges (lod.cpp): the level-wide maximum is set by the rare
  // roughest node, most are far smoother. Exact up to kExactErrorLevels over
  // blocks that measureErrors has measured, geometricError(level) elsewhere.
  float meshError(int level, const PageKey& region) const;
  // Measures one block, a level-1 node (scanned at full resolution once, then kept:
  // 8 bytes a block; about 2 ms on a noise field); false if it already was, or
  // lies outside the field. Not thread-safe.
  bool measureErrors(const PageKey& block) const;
  bool errorsMeasured(const PageKey& block) const;
  // Heights (metres above the origin) of every sample, and rigorous bounds of a node.
  HeightRange heightRange() const { return source_->globalBounds(); }
  HeightRange nodeBounds(const PageKey& node) const;
  // Bounds over samples [x0, x1] x [z0, z1] (clamped to the field).
  HeightRange regionBounds(int x0, int z0, int x1, int z1) const;

  // One sample straight from the source (indices clamped); no cache involved.
  float sample(int ix, int iz) const;
  std::shared_ptr<const HeightPage> page(const PageKey& key) const { return cache_->get(key); }
  const PageCacheStats& cacheStats() const { return cache_->stats(); }

 private:
  Terrain() = default;
  void fillPage(const PageKey& key, HeightPage& page) const;
  void estimateErrors(bool exact);
  double deltaOverRegion(int level, int gx0, int gz0, int cells) const;
  using BlockErrors = std::array<float, kExactErrorLevels>;
  BlockErrors scanBlock(int bx, int bz) const;

  std::unique_ptr<HeightSource> source_;
  std::unique_ptr<PageCache> cache_;
  glm::dvec3 origin_{0.0};
  double spacing_ = 1.0;
  int cellsX_ = 0, cellsZ_ = 0;
  int levelCount_ = 1;
  std::vector<float> errors_;
  // Per level-1 node ("block"), the exact error of levels 1..kExactErrorLevels
  // over it; behind a pointer so that a const Terrain can fill it and still move.
  std::unique_ptr<std::unordered_map<std::int64_t, BlockErrors>> blockErrors_;
};

}  // namespace engine::terrain
