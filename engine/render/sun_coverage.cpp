#include "render/sun_coverage.h"

#include <cmath>

namespace engine {

bool withinNearSunMap(const glm::dmat4& shadowMatrix, const glm::dvec3& lo, const glm::dvec3& hi, double texelWorld) {
  // The normal offset is at most 1.5 texels along each axis (a unit normal).
  const glm::dvec3 pad(1.5 * texelWorld);
  const glm::dvec3 a = lo - pad, b = hi + pad;
  const double low = kSunMapFadeWidth + kSunCoverageMargin, high = 1.0 - low;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec4 p = shadowMatrix * glm::dvec4(i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z, 1.0);
    if (!(std::abs(p.w - 1.0) < 1e-9)) return false;  // not an orthographic box
    if (!(p.x >= low && p.x <= high && p.y >= low && p.y <= high)) return false;
    if (!(p.z >= kSunCoverageMargin && p.z <= 1.0 - kSunCoverageMargin)) return false;
  }
  return true;
}

}  // namespace engine
