#include "asset/tangents.h"

#include <cmath>

namespace engine {
namespace {

// A unit vector orthogonal to `n`: the cross product with the axis least aligned
// with it, which is never close to parallel.
glm::vec3 anyOrthogonal(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const glm::vec3 axis = a.x <= a.y && a.x <= a.z ? glm::vec3(1, 0, 0) : a.y <= a.z ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  return glm::normalize(glm::cross(n, axis));
}

glm::vec3 unitOr(const glm::vec3& v, const glm::vec3& fallback) {
  const float len = glm::length(v);
  return std::isfinite(len) && len > 1e-20f ? v / len : fallback;
}

}  // namespace

// MikkTSpace is the glTF reference for tangents a file leaves out; it is not
// packaged in Debian, so this is the classic method (Lengyel): each triangle's
// uv derivatives dP/du and dP/dv, accumulated per vertex, then Gram-Schmidt against
// the normal. It agrees with MikkTSpace on smooth, non-mirrored meshes and differs
// in how it splits and weights at uv seams.
std::vector<glm::vec4> generateTangents(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                        std::span<const glm::vec2> uvs, std::span<const std::uint32_t> indices) {
  const size_t count = positions.size();
  std::vector<glm::dvec3> tangentSum(count, glm::dvec3(0.0)), bitangentSum(count, glm::dvec3(0.0));
  const size_t corners = indices.empty() ? count : indices.size();
  auto index = [&](size_t i) { return indices.empty() ? std::uint32_t(i) : indices[i]; };
  if (normals.size() == count && uvs.size() == count) {
    for (size_t t = 0; t + 2 < corners; t += 3) {
      const std::uint32_t i0 = index(t), i1 = index(t + 1), i2 = index(t + 2);
      if (i0 >= count || i1 >= count || i2 >= count) continue;
      const glm::dvec3 e1 = glm::dvec3(positions[i1] - positions[i0]), e2 = glm::dvec3(positions[i2] - positions[i0]);
      const glm::dvec2 d1 = glm::dvec2(uvs[i1] - uvs[i0]), d2 = glm::dvec2(uvs[i2] - uvs[i0]);
      const double det = d1.x * d2.y - d2.x * d1.y;
      // No uv area: the triangle says nothing about the directions of u and v.
      if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;
      // dP/du and dP/dv times det; dividing by det would let a sliver of uv space
      // outweigh everything, so each triangle adds unit directions weighted by its
      // area in space.
      const glm::dvec3 sdir = (e1 * d2.y - e2 * d1.y) * (det > 0.0 ? 1.0 : -1.0);
      const glm::dvec3 tdir = (e2 * d1.x - e1 * d2.x) * (det > 0.0 ? 1.0 : -1.0);
      const double area = 0.5 * glm::length(glm::cross(e1, e2));
      const double ls = glm::length(sdir), lt = glm::length(tdir);
      if (!(ls > 0.0) || !(lt > 0.0) || !std::isfinite(area)) continue;
      for (std::uint32_t v : {i0, i1, i2}) {
        tangentSum[v] += sdir / ls * area;
        bitangentSum[v] += tdir / lt * area;
      }
    }
  }
  std::vector<glm::vec4> out(count);
  for (size_t v = 0; v < count; ++v) {
    const glm::vec3 n = unitOr(v < normals.size() ? normals[v] : glm::vec3(0.0f), glm::vec3(0, 0, 1));
    // In double until normalised: sums of huge triangles' areas overflow a float.
    const glm::dvec3 nd(n), sum = tangentSum[v];
    const glm::vec3 t = unitOr(glm::vec3(glm::normalize(sum - nd * glm::dot(nd, sum))), anyOrthogonal(n));
    // glTF's v runs down the image while its normal maps keep +Y up (OpenGL
    // convention), so the bitangent the map expects points along -dP/dv.
    const double side = glm::dot(glm::cross(nd, glm::dvec3(t)), -bitangentSum[v]);
    out[v] = glm::vec4(t, side < 0.0 ? -1.0f : 1.0f);
  }
  return out;
}

}  // namespace engine
