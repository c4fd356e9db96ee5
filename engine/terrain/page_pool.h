#pragma once
// The GPU pool of height pages, sized GL-free: the rasterizer's terrain renderer
// allocates it, and the scene layer selects every renderer's terrain within it
// (scene/terrain_mesh.h), so the tracers never trace a selection the rasterizer
// could not draw.
#include <algorithm>
#include <cstddef>

#include "terrain/page_cache.h"

namespace engine::terrain {

// Pages are packed kPageAtlas x kPageAtlas per array layer (the layer count is
// capped at 2048 on many drivers; the atlas lifts the cap to 32768 pages).
inline constexpr int kPageAtlas = 4;
inline constexpr int kPagesPerLayer = kPageAtlas * kPageAtlas;
// GPU bytes per page slot: kPageSide^2 floats, 17.5 KiB.
inline constexpr std::size_t kGpuPageBytes = kPageSamples * sizeof(float);
// Default GPU budget for height pages: 128 MiB, 7,472 slots. A 16 km field at 1 m
// spacing seen from 40 m up at 1280x720 with a 0.5 px target reads about 4,300.
inline constexpr std::size_t kDefaultGpuPageBudgetBytes = 128ull * 1024 * 1024;
// Below this many slots even the coarsest selection may not fit.
inline constexpr int kMinGpuPageSlots = 512;

// The pool's slots for a byte budget: whole atlas layers, at least kMinGpuPageSlots,
// at most `maxLayers` layers (the driver's GL_MAX_ARRAY_TEXTURE_LAYERS).
inline int pageLayersWithin(std::size_t budgetBytes, int maxLayers) {
  const std::size_t budgetLayers = budgetBytes / (kGpuPageBytes * kPagesPerLayer);
  return int(std::clamp<std::size_t>(budgetLayers, kMinGpuPageSlots / kPagesPerLayer,
                                     std::size_t(std::max(maxLayers, 1))));
}

// The default pool's slots on a driver with GL 4.5's minimum of 2048 layers, which
// the default budget does not reach: what the rasterizer's pool holds by default.
inline constexpr int kMinMaxArrayTextureLayers = 2048;
inline int defaultPageSlots() {
  return pageLayersWithin(kDefaultGpuPageBudgetBytes, kMinMaxArrayTextureLayers) * kPagesPerLayer;
}

}  // namespace engine::terrain
