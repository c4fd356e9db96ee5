#pragma once
// Height pages and their least-recently-used cache. A page holds the samples of one
// quadtree node at that node's own stride (2^level samples), which is all its grid
// ever reads, so a far node costs the same memory as a near one. The cache never
// holds more than its byte budget: inserting past it evicts the oldest pages first.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

#include "terrain/height_source.h"

namespace engine::terrain {

// Grid sizes shared by the CPU selection, the CPU vertex mirror and the shader.
inline constexpr int kPatchQuads = 32;              // quads per side of the drawn grid
inline constexpr int kNodeQuads = 2 * kPatchQuads;  // a node is 2x2 patches
// Node samples plus a one-sample border on each side for central-difference normals.
inline constexpr int kPageSide = kNodeQuads + 3;
inline constexpr std::size_t kPageSamples = std::size_t(kPageSide) * kPageSide;
// What one cached page costs: its heights plus a fixed allowance for the list node,
// the hash entry and the shared_ptr control block.
inline constexpr std::size_t kPageBytes = kPageSamples * sizeof(float) + 128;
// Default CPU budget for height pages: 256 MiB, about 14,900 pages.
inline constexpr std::size_t kDefaultPageCacheBytes = 256ull * 1024 * 1024;

struct PageKey {
  int level = 0;  // 0 = full resolution
  int nx = 0, nz = 0;  // node index at that level
  bool operator==(const PageKey&) const = default;
};

struct PageKeyHash {
  std::size_t operator()(const PageKey& k) const {
    std::uint64_t h = std::uint64_t(unsigned(k.level)) * 0x9E3779B97F4A7C15ull;
    h ^= (std::uint64_t(unsigned(k.nx)) << 32 | unsigned(k.nz)) + (h << 6) + (h >> 2);
    return std::size_t(h ^ (h >> 29));
  }
};

struct HeightPage {
  PageKey key;
  // kPageSide^2 heights (metres above the terrain origin), row-major by z; entry
  // (i + 1, j + 1) is node sample (i, j), i.e. global sample origin + (i, j) * stride.
  std::vector<float> heights;
  // The least and greatest of the samples each of the node's 2 x 2 patches reads,
  // borders out ([qx * kPatchQuads, qx * kPatchQuads + kPatchQuads] in i, and so
  // in j), entry qx + 2 * qz: the heights a patch's grid lies between, for culling.
  std::array<HeightRange, 4> patchRanges{};
  float at(int i, int j) const { return heights[std::size_t(j + 1) * kPageSide + (i + 1)]; }
  void measurePatches();
};

struct PageCacheStats {
  std::size_t bytes = 0;      // held now
  std::size_t peakBytes = 0;  // most ever held
  std::size_t budgetBytes = 0;
  std::size_t pages = 0;
  std::uint64_t hits = 0, misses = 0, evictions = 0;
};

class PageCache {
 public:
  using Generator = std::function<void(const PageKey&, HeightPage&)>;
  PageCache(std::size_t budgetBytes, Generator generate);

  // The page for `key`, generated on a miss. The shared_ptr keeps a page alive
  // for its holder even if the cache evicts it meanwhile.
  std::shared_ptr<const HeightPage> get(const PageKey& key);
  const PageCacheStats& stats() const { return stats_; }
  void clear();

 private:
  using Entry = std::shared_ptr<HeightPage>;
  std::size_t budget_;
  Generator generate_;
  std::list<Entry> lru_;  // most recent first
  std::unordered_map<PageKey, std::list<Entry>::iterator, PageKeyHash> index_;
  PageCacheStats stats_;
};

}  // namespace engine::terrain
