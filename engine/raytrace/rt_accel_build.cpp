#include "raytrace/rt_accel.h"

#include <chrono>
#include <limits>
#include <string>
#include <utility>

#include "scene/shapes.h"

namespace engine::rt {
namespace {

double elapsedSeconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A per-vertex attribute is absent (empty) or has one value per position.
Status checkPerVertex(std::size_t values, std::size_t positions, const std::string& where, const char* what) {
  if (values == 0 || values == positions) return Ok{};
  return makeError(where + ": " + std::to_string(values) + " " + what + " for " + std::to_string(positions) +
                   " positions");
}

}  // namespace

void RtAccel::addSphere(const glm::dvec3& center, double radius, int material) {
  spheresD_.push_back(Sphere<double>{center, radius, material});
  spheresF_.push_back(Sphere<float>{glm::vec3(center), float(radius), material});
  packs_.setSpheres(spheresF_);
  lanes_.addSphere(spheresF_.back());
  updateRoots();
}

void RtAccel::addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material, double extent) {
  const glm::dvec3 n = glm::normalize(normal);
  const glm::dmat3 r(rotationFromTo(glm::dvec3(0, 1, 0), n));
  planeUvs_.push_back(PlaneUv{point, r * glm::dvec3(1, 0, 0), r * glm::dvec3(0, 0, 1), extent});
  const double d = glm::dot(n, point);
  planesD_.push_back(Plane<double>{n, d, material});
  planesF_.push_back(Plane<float>{glm::vec3(n), float(d), material});
  std::vector<ShapePacks::Square> squares;
  for (const PlaneUv& q : planeUvs_) squares.push_back({q.point, q.extent});
  packs_.setPlanes(planesF_, squares);
  lanes_.addPlane(planesF_.back(), planeUvs_.back());
}

int RtAccel::addGroup(std::string name) {
  groups_.emplace_back();
  groups_.back().name = std::move(name);
  return int(groups_.size() - 1);
}

Result<MeshId> RtAccel::addMesh(RtMesh mesh, int materialCount) {
  const std::string where = "mesh " + std::to_string(meshes_.size());
  if (mesh.indices.size() % 3 != 0) return makeError(where + ": index count is not a multiple of 3");
  for (std::uint32_t i : mesh.indices) {
    if (i >= mesh.positions.size()) return makeError(where + ": index " + std::to_string(i) + " out of range");
  }
  if (auto s = checkPerVertex(mesh.normals.size(), mesh.positions.size(), where, "normals"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.uvs.size(), mesh.positions.size(), where, "uvs"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.uvs1.size(), mesh.positions.size(), where, "second-set uvs"); !s) return s.error();
  if (auto s = checkPerVertex(mesh.colors.size(), mesh.positions.size(), where, "colours"); !s) return s.error();
  if (mesh.material < 0 || mesh.material >= materialCount) {
    return makeError(where + ": material " + std::to_string(mesh.material) + " out of range");
  }
  if (mesh.group < 0 || mesh.group >= int(groups_.size())) {
    return makeError(where + ": group " + std::to_string(mesh.group) + " does not exist");
  }
  Group& group = groups_[std::size_t(mesh.group)];
  group.meshes.push_back(std::uint32_t(meshes_.size()));
  group.topologyDirty = true;
  meshes_.push_back(std::move(mesh));
  meshFirstTriangle_.push_back(0);
  return MeshId(meshes_.size() - 1);
}

Status RtAccel::updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  if (id < 0 || id >= MeshId(meshes_.size())) return makeError("mesh " + std::to_string(id) + ": no such mesh");
  RtMesh& mesh = meshes_[std::size_t(id)];
  if (positions.size() != mesh.positions.size()) {
    return makeError("mesh " + std::to_string(id) + ": " + std::to_string(positions.size()) + " positions, expected " +
                     std::to_string(mesh.positions.size()));
  }
  if (!normals.empty() && normals.size() != mesh.normals.size()) {
    return makeError("mesh " + std::to_string(id) + ": " + std::to_string(normals.size()) + " normals, expected " +
                     std::to_string(mesh.normals.size()));
  }
  mesh.positions.assign(positions.begin(), positions.end());
  if (!normals.empty()) mesh.normals.assign(normals.begin(), normals.end());
  groups_[std::size_t(mesh.group)].moved = true;
  return Ok{};
}

void RtAccel::clearMeshes() {
  meshes_.clear();
  meshFirstTriangle_.clear();
  groups_.assign(1, Group{});
  boxedTriangles_ = false;
  updateRoots();
}

std::size_t RtAccel::triangleCount() const {
  std::size_t n = 0;
  for (const Group& g : groups_) n += g.triangles.size();
  return n;
}

void RtAccel::gatherTriangles(int groupIndex) {
  Group& group = groups_[std::size_t(groupIndex)];
  group.triangles.clear();
  group.triangleMesh.clear();
  for (std::uint32_t m : group.meshes) {
    const RtMesh& mesh = meshes_[m];
    meshFirstTriangle_[m] = std::uint32_t(group.triangles.size());
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      group.triangles.push_back(TriangleVerts{mesh.positions[mesh.indices[i]], mesh.positions[mesh.indices[i + 1]],
                                              mesh.positions[mesh.indices[i + 2]]});
      group.triangleMesh.push_back(m);
    }
  }
}

double RtAccel::buildGroup(int groupIndex) {
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles(groupIndex);
  Group& group = groups_[std::size_t(groupIndex)];
  group.bvh.build(group.triangles);
  group.topologyDirty = group.moved = false;
  boxedTriangles_ = triangleCount() > 0;
  updateRoots();
  return elapsedSeconds(start);
}

double RtAccel::refitGroup(int groupIndex) {
  if (groups_[std::size_t(groupIndex)].topologyDirty) return buildGroup(groupIndex);
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles(groupIndex);
  Group& group = groups_[std::size_t(groupIndex)];
  group.bvh.refit(group.triangles);
  group.moved = false;
  updateRoots();
  return elapsedSeconds(start);
}

Bvh::Node RtAccel::noRoots() {
  Bvh::Node node{};
  for (int lane = 0; lane < Bvh::kWidth; ++lane) {
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][lane] = std::numeric_limits<float>::infinity();
      node.box[axis + 3][lane] = -std::numeric_limits<float>::infinity();
    }
    node.child[lane] = Bvh::kNoChild;
  }
  return node;
}

double RtAccel::build() {
  double total = 0.0;
  for (int g = 0; g < groupCount(); ++g) total += buildGroup(g);
  return total;
}

double RtAccel::refit() {
  double total = 0.0;
  for (int g = 0; g < groupCount(); ++g) {
    if (groups_[std::size_t(g)].topologyDirty || groups_[std::size_t(g)].moved) total += refitGroup(g);
  }
  return total;
}

}  // namespace engine::rt
