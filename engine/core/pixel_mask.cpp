#include "core/pixel_mask.h"

namespace engine {
namespace {
std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }
}  // namespace

Status checkMaskSize(const PixelMask* mask, int width, int height) {
  if (mask && (mask->width != width || mask->height != height))
    return makeError("the mask is " + sizeText(mask->width, mask->height) + " pixels, the images " +
                     sizeText(width, height));
  if (mask && mask->count == 0) return makeError("the mask selects no pixel");
  return Ok{};
}

}  // namespace engine
