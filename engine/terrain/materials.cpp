#include "terrain/materials.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "terrain/height_source.h"

namespace engine::terrain {
namespace {

// Value noise whose lattice wraps every `period` cells, so the image tiles.
double tiledNoise(std::uint32_t seed, int octave, double x, double y, int period) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const double u = fx * fx * (3.0 - 2.0 * fx), v = fy * fy * (3.0 - 2.0 * fy);
  auto at = [&](int ix, int iy) {
    return latticeValue(seed, octave, ((ix % period) + period) % period, ((iy % period) + period) % period);
  };
  const double a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * u;
  const double b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * u;
  return a + (b - a) * v;
}

// fBm in [-1, 1] over the image, with the first octave's lattice `cells` wide.
double fbm(std::uint32_t seed, int x, int y, int size, int cells, int octaves) {
  double sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int o = 0; o < octaves; ++o, cells *= 2, amplitude *= 0.5) {
    sum += amplitude * tiledNoise(seed, o, double(x) * cells / size, double(y) * cells / size, cells);
    norm += amplitude;
  }
  return sum / norm;
}

struct Look {
  glm::dvec3 dark, light;
  int cells, octaves;
  double contrast;
  std::uint32_t seed;
};

Look lookOf(TerrainLayer layer) {
  switch (layer) {
    case TerrainLayer::Grass: return {{0.10, 0.22, 0.05}, {0.32, 0.50, 0.14}, 8, 5, 2.2, 11};
    case TerrainLayer::Rock: return {{0.25, 0.23, 0.21}, {0.55, 0.52, 0.48}, 4, 6, 2.6, 23};
    case TerrainLayer::Snow: return {{0.80, 0.84, 0.90}, {0.97, 0.98, 1.00}, 4, 4, 1.5, 37};
  }
  return {};
}

}  // namespace

glm::vec2 layerUvOffset(const glm::dvec3& cameraFromOrigin) {
  const glm::dvec2 tiles = glm::dvec2(cameraFromOrigin.x, cameraFromOrigin.z) / double(kLayerTileMetres);
  return glm::vec2(tiles - glm::floor(tiles));
}

Image makeLayerImage(TerrainLayer layer, int size) {
  const Look look = lookOf(layer);
  Image image(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double n = fbm(look.seed, x, y, size, look.cells, look.octaves);
      const double t = std::clamp(0.5 + 0.5 * n * look.contrast, 0.0, 1.0);
      const glm::dvec3 c = glm::mix(look.dark, look.light, t);
      std::uint8_t* p = image.at(x, y);
      // Stored sRGB-encoded by a plain 1/2.2 power; the texture is sampled as sRGB.
      for (int ch = 0; ch < 3; ++ch) p[ch] = std::uint8_t(std::lround(255.0 * std::pow(c[ch], 1.0 / 2.2)));
      p[3] = 255;
    }
  }
  return image;
}

}  // namespace engine::terrain
