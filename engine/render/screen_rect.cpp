#include "render/screen_rect.h"

namespace engine {

glm::ivec4 sphereScreenRect(const glm::dmat4& viewProjection, const glm::dvec3& center, double radius, int width,
                            int height) {
  glm::dvec2 lo(1e300), hi(-1e300);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 sign((corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0, (corner & 4) ? 1.0 : -1.0);
    const glm::dvec4 clip = viewProjection * glm::dvec4(center + sign * radius, 1.0);
    if (!(clip.w > 0.0)) return {0, 0, width, height};
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  const glm::dvec2 size(width, height);
  const glm::dvec2 p0 = glm::clamp(glm::floor((lo * 0.5 + 0.5) * size) - 1.0, glm::dvec2(0.0), size);
  const glm::dvec2 p1 = glm::clamp(glm::ceil((hi * 0.5 + 0.5) * size) + 1.0, glm::dvec2(0.0), size);
  return {int(p0.x), int(p0.y), int(p1.x), int(p1.y)};
}

}  // namespace engine
