#include "render/textures.h"

#include <algorithm>

namespace engine {
namespace {
void put(Image& image, int x, int y, glm::u8vec3 c) {
  std::uint8_t* p = image.at(x, y);
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
  p[3] = 255;
}
}  // namespace

Image makeChecker(int size, int cells, glm::u8vec3 a, glm::u8vec3 b) {
  Image image(size, size);
  const int cell = std::max(1, size / cells);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) put(image, x, y, ((x / cell + y / cell) % 2) ? b : a);
  }
  return image;
}

Image makeTiles(int size, int tiles, glm::u8vec3 tile, glm::u8vec3 grout) {
  Image image(size, size);
  const int cell = std::max(2, size / tiles);
  const int line = std::max(1, cell / 16);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int tx = x / cell, ty = y / cell;
      const bool isGrout = x % cell < line || y % cell < line;
      // A fixed hash of the tile index: varied, and the same on every run.
      const int tint = int((unsigned(tx * 73856093) ^ unsigned(ty * 19349663)) % 41u) - 20;
      const glm::u8vec3 c(std::clamp(tile.r + tint, 0, 255), std::clamp(tile.g + tint, 0, 255),
                          std::clamp(tile.b + tint, 0, 255));
      put(image, x, y, isGrout ? grout : c);
    }
  }
  return image;
}

}  // namespace engine
