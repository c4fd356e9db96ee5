#include "core/sheen_table.h"

#include <algorithm>
#include <cmath>

#include "core/brdf.h"

namespace engine {

float sheenAlbedoEntry(float nDotV, float roughness, int steps) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const glm::vec3 v(std::sqrt(std::max(1.0f - nDotV * nDotV, 0.0f)), 0.0f, nDotV);
  // cos theta = t^2 with t uniform: the cells crowd toward the horizon, where a
  // smooth sheen's lobe lies (48 cells then agree with 2048 to 0.1 %; uniform theta
  // cells were 3 % off at grazing views). The lobe is symmetric about the plane of n
  // and v: phi over [0, pi], doubled.
  const double dt = 1.0 / steps, dPhi = M_PI / steps;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 0.5) * dt, cosTheta = t * t, sinTheta = std::sqrt(1.0 - cosTheta * cosTheta);
    const double cellWeight = cosTheta * 2.0 * t * dt * dPhi;  // N.L d(cos theta) d(phi)
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) * dPhi;
      const glm::vec3 l(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)), float(cosTheta));
      sum += double(brdf::sheenBrdf(n, v, l, roughness)) * cellWeight;
    }
  }
  return float(2.0 * sum);
}

SheenTable makeSheenTable(int size, int steps) {
  SheenTable table;
  table.size = size;
  table.texels.resize(size_t(size * size));
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const float root = float(i) / float(size - 1);
      table.texels[size_t(j * size + i)] = sheenAlbedoEntry(root * root, float(j) / float(size - 1), steps);
    }
  }
  return table;
}

float SheenTable::lookup(float nDotV, float roughness) const {
  // Texel space of the coordinate the shader samples at (GL_LINEAR's weights).
  const glm::vec2 x = brdf::sheenTableCoord(nDotV, roughness) * float(size) - glm::vec2(0.5f);
  const int x0 = std::clamp(int(std::floor(x.x)), 0, size - 1), y0 = std::clamp(int(std::floor(x.y)), 0, size - 1);
  const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
  const float wx = x.x - float(x0), wy = x.y - float(y0);
  auto at = [&](int i, int j) { return texels[size_t(j * size + i)]; };
  const float bottom = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * wx;
  const float top = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * wx;
  return bottom + (top - bottom) * wy;
}

const SheenTable& sheenTable() {
  static const SheenTable table = makeSheenTable(int(brdf::SHEEN_TABLE_SIZE), 48);
  return table;
}

}  // namespace engine
