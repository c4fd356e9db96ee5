#pragma once
// Which pixels an image comparison counts (imgdiff --mask M.png): an error outside
// the mask is left out of every figure, so a comparison can ignore a region known to
// differ (a sky, a window, the trade panel) or measure one part of the picture alone.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace engine {

struct PixelMask {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> selected;  // width * height, 1 where counted, top row first
  std::size_t count = 0;               // pixels selected
};

// core/image.h's maskFromImage makes one from a picture.

// Whether pixel i counts: every pixel without a mask.
inline bool counts(const PixelMask* mask, std::size_t i) { return !mask || mask->selected[i] != 0; }

// An error unless the mask is absent, or of the compared images' size and selects
// some pixel.
Status checkMaskSize(const PixelMask* mask, int width, int height);

}  // namespace engine
