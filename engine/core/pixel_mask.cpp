#include "core/pixel_mask.h"

#include "core/image.h"

namespace engine {
namespace {
std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }
}  // namespace

Result<PixelMask> maskFromImage(const Image& image, int width, int height, const std::string& name) {
  if (image.width != width || image.height != height)
    return makeError(name + ": the mask is " + sizeText(image.width, image.height) + " pixels, the images " +
                     sizeText(width, height));
  PixelMask mask;
  mask.width = width;
  mask.height = height;
  mask.selected.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t i = 0; i < mask.selected.size(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    mask.selected[i] = (p[0] | p[1] | p[2]) != 0;
    mask.count += mask.selected[i];
  }
  if (mask.count == 0) return makeError(name + ": the mask selects no pixel (every pixel is black)");
  return mask;
}

Status checkMaskSize(const PixelMask* mask, int width, int height) {
  if (mask && (mask->width != width || mask->height != height))
    return makeError("the mask is " + sizeText(mask->width, mask->height) + " pixels, the images " +
                     sizeText(width, height));
  if (mask && mask->count == 0) return makeError("the mask selects no pixel");
  return Ok{};
}

}  // namespace engine
