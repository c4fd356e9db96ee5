#include "terrain/page_cache.h"

#include <algorithm>

namespace engine::terrain {

void HeightPage::measurePatches() {
  for (int q = 0; q < 4; ++q) {
    const int i0 = (q & 1) * kPatchQuads, j0 = (q >> 1) * kPatchQuads;
    HeightRange& r = patchRanges[std::size_t(q)];
    r = {at(i0, j0), at(i0, j0)};
    for (int j = j0; j <= j0 + kPatchQuads; ++j) {
      for (int i = i0; i <= i0 + kPatchQuads; ++i) {
        r.min = std::min(r.min, at(i, j));
        r.max = std::max(r.max, at(i, j));
      }
    }
  }
}

PageCache::PageCache(std::size_t budgetBytes, Generator generate)
    : budget_(budgetBytes), generate_(std::move(generate)) {
  stats_.budgetBytes = budget_;
}

std::shared_ptr<const HeightPage> PageCache::get(const PageKey& key) {
  if (auto it = index_.find(key); it != index_.end()) {
    ++stats_.hits;
    lru_.splice(lru_.begin(), lru_, it->second);
    return *it->second;
  }
  ++stats_.misses;
  auto page = std::make_shared<HeightPage>();
  page->key = key;
  page->heights.resize(kPageSamples);
  generate_(key, *page);
  page->measurePatches();
  // Evict before inserting, so the budget holds at every moment, not just after.
  while (!lru_.empty() && stats_.bytes + kPageBytes > budget_) {
    index_.erase(lru_.back()->key);
    lru_.pop_back();
    stats_.bytes -= kPageBytes;
    ++stats_.evictions;
  }
  // A budget under one page caches nothing; the caller still gets its page.
  if (stats_.bytes + kPageBytes <= budget_) {
    lru_.push_front(page);
    index_[key] = lru_.begin();
    stats_.bytes += kPageBytes;
    stats_.peakBytes = std::max(stats_.peakBytes, stats_.bytes);
  }
  stats_.pages = lru_.size();
  return page;
}

void PageCache::clear() {
  lru_.clear();
  index_.clear();
  stats_.bytes = 0;
  stats_.pages = 0;
}

}  // namespace engine::terrain
