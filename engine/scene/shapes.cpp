#include "scene/shapes.h"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace engine {

namespace {

// Two triangles per cell of a grid of (rows + 1) x (columns + 1) vertices laid out
// row by row: counter-clockwise seen from the side the plane's +y and the sphere's
// outside face.
void appendGridIndices(ShapeData& mesh, int rows, int columns) {
  const auto row = static_cast<std::uint32_t>(columns + 1);
  for (std::uint32_t j = 0; j < std::uint32_t(rows); ++j) {
    for (std::uint32_t i = 0; i < std::uint32_t(columns); ++i) {
      const std::uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  }
}

}  // namespace

glm::dmat4 rotationFromTo(const glm::dvec3& from, const glm::dvec3& to) {
  const glm::dvec3 axis = glm::cross(from, to);
  const double c = glm::dot(from, to);
  if (glm::length(axis) < 1e-12) {
    return c > 0.0 ? glm::dmat4(1.0) : glm::rotate(glm::dmat4(1.0), glm::pi<double>(), glm::dvec3(1, 0, 0));
  }
  return glm::rotate(glm::dmat4(1.0), std::atan2(glm::length(axis), c), glm::normalize(axis));
}

ShapeData shapeForPrimitive(const PrimitiveDesc& p) {
  switch (p.type) {
    case PrimitiveType::Sphere: return makeSphere(1.0f, 48, 96);
    case PrimitiveType::Box: return makeCube(1.0f);
    // Finely divided so per-vertex work (fog, lighting) stays well conditioned.
    case PrimitiveType::Plane: return makePlane(2.0f, 16, 2.0f);
  }
  return {};
}

double planeExtent(const PrimitiveDesc& p, double farPlane) { return p.extent > 0.0 ? p.extent : farPlane; }

glm::dmat4 primitiveTransform(const PrimitiveDesc& p, double farPlane) {
  switch (p.type) {
    case PrimitiveType::Sphere:
      return glm::scale(glm::translate(glm::dmat4(1.0), p.center), glm::dvec3(p.radius));
    case PrimitiveType::Box:
      return glm::scale(glm::translate(glm::dmat4(1.0), (p.min + p.max) * 0.5), p.max - p.min);
    case PrimitiveType::Plane: {
      const double extent = planeExtent(p, farPlane);
      return glm::translate(glm::dmat4(1.0), p.point) * rotationFromTo({0, 1, 0}, p.normal) *
             glm::scale(glm::dmat4(1.0), glm::dvec3(extent, 1.0, extent));
    }
  }
  return glm::dmat4(1.0);
}

bool isOpaquePlane(const SceneDesc& scene, std::size_t index) {
  const PrimitiveDesc& p = scene.primitives[index];
  return p.type == PrimitiveType::Plane && !scene.materials[size_t(p.material)].layers.transmissive();
}

std::array<glm::dvec3, 4> planeCorners(const glm::dmat4& world) {
  const glm::dvec2 local[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  std::array<glm::dvec3, 4> out;
  for (size_t c = 0; c < 4; ++c) out[c] = glm::dvec3(world * glm::dvec4(local[c].x, 0.0, local[c].y, 1.0));
  return out;
}

ShapeData makePlane(float size, int cells, float uvRepeat) {
  ShapeData mesh;
  const float half = size * 0.5f;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const float u = float(i) / float(cells), v = float(j) / float(cells);
      mesh.vertices.push_back(
          {{-half + u * size, 0.0f, -half + v * size}, {0, 1, 0}, {u * uvRepeat, v * uvRepeat}});
    }
  }
  appendGridIndices(mesh, cells, cells);
  return mesh;
}

ShapeData makeCube(float size) {
  ShapeData mesh;
  const float h = size * 0.5f;
  // Each face: normal, and two axes spanning it (u, v) with u x v = normal.
  const glm::vec3 faces[6][3] = {
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
  for (const auto& f : faces) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& c : corners) {
      const glm::vec3 p = (f[0] + f[1] * (c.x * 2 - 1) + f[2] * (c.y * 2 - 1)) * h;
      mesh.vertices.push_back({p, f[0], c});
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  return mesh;
}

ShapeData makeSphere(float radius, int rings, int segments) {
  ShapeData mesh;
  for (int r = 0; r <= rings; ++r) {
    const float v = float(r) / float(rings);
    const float theta = v * glm::pi<float>();
    for (int s = 0; s <= segments; ++s) {
      const float u = float(s) / float(segments);
      const float phi = u * glm::two_pi<float>();
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
      mesh.vertices.push_back({n * radius, n, {u, v}});
    }
  }
  appendGridIndices(mesh, rings, segments);
  return mesh;
}

}  // namespace engine
