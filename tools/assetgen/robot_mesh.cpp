#include "robot_mesh.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace assetgen {

namespace {

// One cross-section of a tube: where it sits, which way the tube runs there, how
// wide it is, where it falls in the texture and which joints move it.
struct Ring {
  glm::vec3 center{0.0f};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  glm::vec2 radius{0.0f};
  float v = 0.0f;  // fraction of the part's length
  std::array<std::uint8_t, 4> joints{};
  std::array<float, 4> weights{};
};

float segmentLength(const BodyPart& part, size_t k) {
  return glm::distance(part.points[k], part.points[k + 1]);
}

// The axis at a point averages the segments on either side, so that rings at a bend
// tilt halfway and neighbouring rings do not cut through each other.
glm::vec3 pointAxis(const BodyPart& part, size_t i) {
  const size_t last = part.points.size() - 1;
  glm::vec3 axis{0.0f};
  if (i > 0) axis += glm::normalize(part.points[i] - part.points[i - 1]);
  if (i < last) axis += glm::normalize(part.points[i + 1] - part.points[i]);
  return glm::normalize(axis);
}

// Skin binding of a ring `arc` metres along the part that lies in `segment`: a smooth
// blend between the two joints meeting at the nearest inner point, or one joint.
void bindRing(const BodyPart& part, const std::vector<float>& arcAt, size_t segment, float arc,
              Ring& ring) {
  int first = part.joints[segment], second = first;
  float secondWeight = 0.0f;
  for (size_t k = 1; k + 1 < part.points.size(); ++k) {
    if (part.joints[k - 1] == part.joints[k]) continue;
    const float half =
        std::min(part.blend, 0.45f * std::min(segmentLength(part, k - 1), segmentLength(part, k)));
    const float d = arc - arcAt[k];
    if (std::abs(d) >= half) continue;
    first = part.joints[k - 1];
    second = part.joints[k];
    const float t = (d + half) / (2.0f * half);
    secondWeight = t * t * (3.0f - 2.0f * t);
  }
  const float steps = static_cast<float>(kWeightSteps);
  secondWeight = std::round(secondWeight * steps) / steps;
  if (secondWeight <= 0.0f || secondWeight >= 1.0f) {
    const int only = secondWeight >= 1.0f ? second : first;
    ring.joints = {static_cast<std::uint8_t>(only), 0, 0, 0};
    ring.weights = {1.0f, 0.0f, 0.0f, 0.0f};
    return;
  }
  ring.joints = {static_cast<std::uint8_t>(first), static_cast<std::uint8_t>(second), 0, 0};
  ring.weights = {1.0f - secondWeight, secondWeight, 0.0f, 0.0f};
}

// Rings spaced about `ringSpacing` apart, with one exactly at every point so that
// the blend between two joints is centred on a ring.
std::vector<Ring> sweepRings(const BodyPart& part) {
  std::vector<float> arcAt{0.0f};
  for (size_t k = 0; k + 1 < part.points.size(); ++k) {
    arcAt.push_back(arcAt.back() + segmentLength(part, k));
  }
  const float total = arcAt.back();
  std::vector<Ring> rings;
  for (size_t k = 0; k + 1 < part.points.size(); ++k) {
    const int steps =
        std::max(1, static_cast<int>(std::ceil(segmentLength(part, k) / part.ringSpacing)));
    const bool lastSegment = k + 2 == part.points.size();
    for (int i = 0; i <= steps; ++i) {
      if (i == steps && !lastSegment) break;  // the next segment starts with this ring
      const float t = static_cast<float>(i) / static_cast<float>(steps);
      Ring ring;
      ring.center = glm::mix(part.points[k], part.points[k + 1], t);
      ring.axis = glm::normalize(glm::mix(pointAxis(part, k), pointAxis(part, k + 1), t));
      ring.radius = glm::mix(part.radii[k], part.radii[k + 1], t);
      const float arc = glm::mix(arcAt[k], arcAt[k + 1], t);
      ring.v = arc / total;
      bindRing(part, arcAt, k, arc, ring);
      rings.push_back(ring);
    }
  }
  return rings;
}

float superellipse(float x, float exponent) {
  return std::copysign(std::pow(std::abs(x), 2.0f / exponent), x);
}

// Position of side `j` on a ring; j = 0 is the back (the texture seam), j = sides/2
// the front.
glm::vec3 ringPoint(const BodyPart& part, const Ring& ring, int j) {
  const glm::vec3 front = glm::normalize(part.front - glm::dot(part.front, ring.axis) * ring.axis);
  const glm::vec3 side = glm::cross(ring.axis, front);
  const float angle = glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(part.sides);
  return ring.center + ring.radius.x * superellipse(std::sin(angle), part.squareness) * side +
         ring.radius.y * superellipse(-std::cos(angle), part.squareness) * front;
}

Vertex makeVertex(const Ring& ring, glm::vec3 position, glm::vec3 normal, glm::vec2 uv) {
  Vertex v;
  v.position = position;
  v.normal = normal;
  v.uv = uv;
  v.joints = ring.joints;
  v.weights = ring.weights;
  return v;
}

// Pushes triangle (a, b, c), or (a, c, b) when that is the one facing `outward`.
void pushTriangle(const std::vector<Vertex>& vertices, std::vector<std::uint16_t>& indices,
                  std::uint16_t a, std::uint16_t b, std::uint16_t c, glm::vec3 outward) {
  const glm::vec3 n = glm::cross(vertices[b].position - vertices[a].position,
                                 vertices[c].position - vertices[a].position);
  if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
  indices.insert(indices.end(), {a, b, c});
}

void appendCap(const BodyPart& part, const Ring& ring, glm::vec3 outward,
               std::vector<Vertex>& vertices, std::vector<std::uint16_t>& indices) {
  const AtlasCell cap = atlasCell(CellId::Cap);
  const auto capUv = [&](float angle, float scale) {
    const glm::vec2 offset{std::cos(angle), std::sin(angle)};
    return glm::mix(cap.min, cap.max, glm::vec2(0.5f) + scale * offset);
  };
  const auto center = static_cast<std::uint16_t>(vertices.size());
  vertices.push_back(makeVertex(ring, ring.center, outward, capUv(0.0f, 0.0f)));
  for (int j = 0; j < part.sides; ++j) {
    const float angle =
        glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(part.sides);
    vertices.push_back(makeVertex(ring, ringPoint(part, ring, j), outward, capUv(angle, 0.45f)));
  }
  for (int j = 0; j < part.sides; ++j) {
    const auto a = static_cast<std::uint16_t>(center + 1 + j);
    const auto b = static_cast<std::uint16_t>(center + 1 + (j + 1) % part.sides);
    pushTriangle(vertices, indices, center, a, b, outward);
  }
}

}  // namespace

void appendBodyPart(const BodyPart& part, std::vector<Vertex>& vertices,
                    std::vector<std::uint16_t>& indices) {
  const std::vector<Ring> rings = sweepRings(part);
  const int ringCount = static_cast<int>(rings.size());
  const int sides = part.sides;
  std::vector<glm::vec3> grid;
  for (const Ring& ring : rings) {
    for (int j = 0; j < sides; ++j) grid.push_back(ringPoint(part, ring, j));
  }
  const auto at = [&](int r, int j) -> const glm::vec3& {
    return grid[static_cast<size_t>(std::clamp(r, 0, ringCount - 1) * sides + (j + sides) % sides)];
  };
  const AtlasCell cell = atlasCell(part.cell);
  const auto base = static_cast<std::uint16_t>(vertices.size());
  // One more column than sides: the seam needs u = 0 and u = 1 on the same spot.
  for (int r = 0; r < ringCount; ++r) {
    for (int j = 0; j <= sides; ++j) {
      // Central differences around and along the surface give smooth normals that
      // follow the taper and the boxy cross-section alike.
      const glm::vec3 around = at(r, j + 1) - at(r, j - 1);
      const glm::vec3 along = at(r + 1, j) - at(r - 1, j);
      glm::vec3 normal = glm::normalize(glm::cross(around, along));
      if (glm::dot(normal, at(r, j) - rings[r].center) < 0.0f) normal = -normal;
      const glm::vec2 uv{
          glm::mix(cell.min.x, cell.max.x, static_cast<float>(j) / static_cast<float>(sides)),
          glm::mix(cell.min.y, cell.max.y, rings[r].v)};
      vertices.push_back(makeVertex(rings[r], at(r, j), normal, uv));
    }
  }
  const int columns = sides + 1;
  for (int r = 0; r + 1 < ringCount; ++r) {
    for (int j = 0; j < sides; ++j) {
      const auto index = [&](int rr, int jj) {
        return static_cast<std::uint16_t>(base + rr * columns + jj);
      };
      const glm::vec3 outward = vertices[index(r, j)].normal + vertices[index(r + 1, j + 1)].normal;
      pushTriangle(vertices, indices, index(r, j), index(r, j + 1), index(r + 1, j + 1), outward);
      pushTriangle(vertices, indices, index(r, j), index(r + 1, j + 1), index(r + 1, j), outward);
    }
  }
  appendCap(part, rings.front(), -rings.front().axis, vertices, indices);
  appendCap(part, rings.back(), rings.back().axis, vertices, indices);
}

}  // namespace assetgen
