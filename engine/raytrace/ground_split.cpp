#include "raytrace/ground_split.h"

#include <cstdint>
#include <limits>
#include <vector>

#include "scene/shapes.h"

namespace engine::rt {
namespace {

// The triangles `keep` names (three indices each, into mesh.indices' triangles) as a
// mesh of their own: the vertices they use, renumbered in the order first met.
RtMesh subset(const RtMesh& mesh, const std::vector<std::uint32_t>& keep) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(mesh.positions.size(), kUnused);
  RtMesh out;
  out.material = mesh.material;
  out.group = mesh.group;
  const auto copyVertex = [&](std::uint32_t v) {
    out.positions.push_back(mesh.positions[v]);
    if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[v]);
    if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v]);
    if (!mesh.uvs1.empty()) out.uvs1.push_back(mesh.uvs1[v]);
    if (!mesh.colors.empty()) out.colors.push_back(mesh.colors[v]);
  };
  for (const std::uint32_t triangle : keep) {
    for (std::uint32_t corner = 0; corner < 3; ++corner) {
      const std::uint32_t v = mesh.indices[3 * std::size_t(triangle) + corner];
      if (remap[v] == kUnused) {
        remap[v] = std::uint32_t(out.positions.size());
        copyVertex(v);
      }
      out.indices.push_back(remap[v]);
    }
  }
  return out;
}

}  // namespace

std::optional<GroundPlane> groundPlane(const SceneDesc& scene) {
  std::optional<GroundPlane> best;
  double bestExtent = 0.0;
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    if (!isOpaquePlane(scene, i)) continue;
    const PrimitiveDesc& p = scene.primitives[i];
    const double extent = planeExtent(p, scene.camera.farPlane);
    if (best && extent <= bestExtent) continue;
    const glm::dvec3 normal = glm::normalize(p.normal);
    GroundPlane plane{normal, -glm::dot(normal, p.point)};
    const double eye = plane.signedDistance(scene.camera.position);
    if (!(eye != 0.0)) continue;
    if (eye < 0.0) plane = GroundPlane{-plane.normal, -plane.offset};
    best = plane;
    bestExtent = extent;
  }
  return best;
}

RtMesh takeTrianglesBehind(RtMesh& mesh, const GroundPlane& ground) {
  std::vector<std::uint32_t> behind, rest;
  const auto isBehind = [&](std::uint32_t v) { return ground.signedDistance(glm::dvec3(mesh.positions[v])) < 0.0; };
  for (std::uint32_t t = 0; 3 * std::size_t(t) + 2 < mesh.indices.size(); ++t) {
    const std::uint32_t* corner = &mesh.indices[3 * std::size_t(t)];
    (isBehind(corner[0]) && isBehind(corner[1]) && isBehind(corner[2]) ? behind : rest).push_back(t);
  }
  RtMesh out = subset(mesh, behind);
  if (!behind.empty()) mesh = subset(mesh, rest);
  return out;
}

}  // namespace engine::rt
