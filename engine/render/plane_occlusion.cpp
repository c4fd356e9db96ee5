#include "render/plane_occlusion.h"

#include <algorithm>
#include <cmath>

#include "scene/shapes.h"

namespace engine::cull {

namespace {

// Sutherland-Hodgman in clip space against one plane, `side(v) >= 0` inside.
template <typename Side>
std::vector<glm::dvec4> clipPolygon(const std::vector<glm::dvec4>& polygon, Side side) {
  std::vector<glm::dvec4> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec4& a = polygon[i];
    const glm::dvec4& b = polygon[(i + 1) % polygon.size()];
    const double sa = side(a), sb = side(b);
    if (sa >= 0.0) out.push_back(a);
    if ((sa >= 0.0) != (sb >= 0.0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
  }
  return out;
}

glm::dvec2 toPixels(const glm::dvec4& clip, glm::dvec2 viewport) {
  return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * viewport;
}

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

// How far `p` lies inside the edge a -> b of a counter-clockwise outline, pixels.
double insideDistance(glm::dvec2 a, glm::dvec2 b, glm::dvec2 p) {
  const double length = glm::length(b - a);
  return length > 0.0 ? cross2(b - a, p - a) / length : -1.0;
}

}  // namespace

std::optional<ScreenQuad> screenQuad(const std::array<glm::dvec3, 4>& corners, const glm::dmat4& viewProjection,
                                     glm::dvec2 viewport) {
  ScreenQuad quad;
  quad.normal = glm::cross(corners[1] - corners[0], corners[3] - corners[0]);
  const double length = glm::length(quad.normal);
  if (!(length > 0.0)) return std::nullopt;
  quad.normal /= length;
  quad.offset = -glm::dot(quad.normal, corners[0]);
  if (quad.offset < 0.0) {
    quad.normal = -quad.normal;
    quad.offset = -quad.offset;
  }
  if (!(quad.offset > 0.0)) return std::nullopt;
  std::vector<glm::dvec4> clip;
  for (const glm::dvec3& c : corners) clip.push_back(viewProjection * glm::dvec4(c, 1.0));
  // -w <= z <= w holds GL's near plane whichever way depth runs (reverse-Z's
  // 0..w has it at z = w, the default -w..w at z = -w); a far part kept is
  // harmless, as whatever lies behind it is beyond the far plane too.
  clip = clipPolygon(clip, [](const glm::dvec4& v) { return v.w - v.z; });
  clip = clipPolygon(clip, [](const glm::dvec4& v) { return v.w + v.z; });
  if (clip.size() < 3) return std::nullopt;
  double area = 0.0;
  for (const glm::dvec4& v : clip) {
    if (!(v.w > 0.0)) return std::nullopt;
    quad.outline.push_back(toPixels(v, viewport));
  }
  for (size_t i = 0; i < quad.outline.size(); ++i) area += cross2(quad.outline[i], quad.outline[(i + 1) % quad.outline.size()]);
  if (!(std::abs(area) > 0.0)) return std::nullopt;
  if (area < 0.0) std::reverse(quad.outline.begin(), quad.outline.end());
  return quad;
}

std::vector<ScreenQuad> opaquePlanes(const SceneDesc& scene, const glm::dvec3& eye, const glm::dmat4& viewProjection,
                                     glm::dvec2 viewport, int skip) {
  std::vector<ScreenQuad> quads;
  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    if (int(i) == skip || !isOpaquePlane(scene, i)) continue;
    auto corners = planeCorners(primitiveTransform(scene.primitives[i], scene.camera.farPlane));
    for (glm::dvec3& c : corners) c -= eye;
    if (auto q = screenQuad(corners, viewProjection, viewport)) quads.push_back(std::move(*q));
  }
  return quads;
}

bool hidesBox(const ScreenQuad& quad, const glm::dvec3& lo, const glm::dvec3& hi, const glm::dmat4& viewProjection,
              glm::dvec2 viewport, double pixelMargin) {
  const size_t n = quad.outline.size();
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    const double behind = -(glm::dot(quad.normal, corner) + quad.offset);
    if (!(behind >= kPlaneDepthMargin * quad.offset + kPlaneRoundingMargin * glm::length(corner))) return false;
    const glm::dvec4 clip = viewProjection * glm::dvec4(corner, 1.0);
    if (!(clip.w > 0.0)) return false;
    const glm::dvec2 p = toPixels(clip, viewport);
    for (size_t e = 0; e < n; ++e) {
      if (!(insideDistance(quad.outline[e], quad.outline[(e + 1) % n], p) >= pixelMargin)) return false;
    }
  }
  return true;
}

}  // namespace engine::cull
