#pragma once
// The screen-space error a CDLOD selection really has, measured against the
// full-resolution grid: shared by micro_bench's LOD table and bench/terrain_frames.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "terrain/lod.h"
#include "terrain/terrain.h"

namespace engine::terrain::bench {

// Largest screen-space error (pixels) of the drawn surface: at every full-resolution
// sample under a drawn triangle, the vertical gap to the true sample, projected at
// that sample's true distance.
inline double measuredScreenError(const Terrain& t, const LodSelection& s, const LodCamera& camera) {
  const double k = camera.viewportHeight / (2.0 * std::tan(camera.fovY / 2));
  const glm::dvec3 rel = camera.position - t.origin();
  double worst = 0.0;
  for (const LodPatch& p : s.patches) {
    const auto v = patchVertices(t, s, p);
    auto toSample = [&](const glm::vec3& x) {
      return glm::dvec3((x.x + rel.x) / t.spacing(), x.y + rel.y, (x.z + rel.z) / t.spacing());
    };
    auto tri = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
      const double area = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
      if (std::abs(area) < 1e-9) return;
      const int x0 = int(std::ceil(std::min({a.x, b.x, c.x}))), x1 = int(std::floor(std::max({a.x, b.x, c.x})));
      const int z0 = int(std::ceil(std::min({a.z, b.z, c.z}))), z1 = int(std::floor(std::max({a.z, b.z, c.z})));
      for (int z = z0; z <= z1; ++z)
        for (int x = x0; x <= x1; ++x) {
          const double w1 = ((x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z)) / area;
          const double w2 = ((b.x - a.x) * (z - a.z) - (x - a.x) * (b.z - a.z)) / area;
          const double w0 = 1.0 - w1 - w2;
          if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
          const double drawn = w0 * a.y + w1 * b.y + w2 * c.y;
          const double truth = t.sample(x, z);
          const glm::dvec3 d(x * t.spacing() - rel.x, truth - rel.y, z * t.spacing() - rel.z);
          worst = std::max(worst, std::abs(drawn - truth) * k / std::max(glm::length(d), 1e-3));
        }
    };
    const int n = kPatchQuads + 1;
    for (int j = 0; j < kPatchQuads; ++j)
      for (int i = 0; i < kPatchQuads; ++i) {
        const glm::dvec3 a = toSample(v[std::size_t(j) * n + i]), b = toSample(v[std::size_t(j) * n + i + 1]);
        const glm::dvec3 c = toSample(v[std::size_t(j + 1) * n + i + 1]), d = toSample(v[std::size_t(j + 1) * n + i]);
        tri(a, c, b);
        tri(a, d, c);
      }
  }
  return worst;
}

}  // namespace engine::terrain::bench
