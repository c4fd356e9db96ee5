#include "raytrace/rt_scene.h"

#include <chrono>
#include <string>

namespace engine::rt {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A box as 12 triangles, wound counter-clockwise seen from outside, flat shaded.
RtMesh boxMesh(const glm::dvec3& lo, const glm::dvec3& hi, int material) {
  RtMesh mesh;
  mesh.material = material;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back(glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z));
  }
  // Faces as corner quads (a, b, c, d) ordered around the outward normal.
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    mesh.indices.insert(mesh.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  }
  return mesh;
}

}  // namespace

RtScene::RtScene() {
  MaterialDesc fallback;
  fallback.name = "default";
  materials_.push_back(fallback);
}

Result<RtScene> RtScene::fromSceneDesc(const SceneDesc& desc) {
  RtScene scene;
  if (!desc.materials.empty()) scene.materials_ = desc.materials;
  scene.camera_ = desc.camera;
  scene.lights_ = desc.lights;
  scene.sky_ = desc.sky;
  scene.ambientSky_ = ambientSkyColor(desc);
  scene.ambientGround_ = ambientGroundColor(desc);
  scene.render_ = desc.render;
  const int materialCount = int(scene.materials_.size());
  for (std::size_t i = 0; i < desc.primitives.size(); ++i) {
    const PrimitiveDesc& p = desc.primitives[i];
    if (p.material < 0 || p.material >= materialCount) {
      return makeError(desc.path + ": primitive " + std::to_string(i) + ": material " +
                       std::to_string(p.material) + " out of range");
    }
    switch (p.type) {
      case PrimitiveType::Sphere:
        scene.addSphere(p.center, p.radius, p.material);
        break;
      case PrimitiveType::Plane:
        scene.addPlane(p.point, p.normal, p.material);
        break;
      case PrimitiveType::Box: {
        auto id = scene.addMesh(boxMesh(p.min, p.max, p.material));
        if (!id) return id.error();
        break;
      }
    }
  }
  scene.build();
  return scene;
}

int RtScene::addMaterial(const MaterialDesc& material) {
  materials_.push_back(material);
  return int(materials_.size() - 1);
}

void RtScene::addSphere(const glm::dvec3& center, double radius, int material) {
  spheresD_.push_back(Sphere<double>{center, radius, material});
  spheresF_.push_back(Sphere<float>{glm::vec3(center), float(radius), material});
}

void RtScene::addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material) {
  const glm::dvec3 n = glm::normalize(normal);
  const double d = glm::dot(n, point);
  planesD_.push_back(Plane<double>{n, d, material});
  planesF_.push_back(Plane<float>{glm::vec3(n), float(d), material});
}

Result<MeshId> RtScene::addMesh(RtMesh mesh) {
  const std::string where = "mesh " + std::to_string(meshes_.size());
  if (mesh.indices.size() % 3 != 0) return makeError(where + ": index count is not a multiple of 3");
  for (std::uint32_t i : mesh.indices) {
    if (i >= mesh.positions.size()) return makeError(where + ": index " + std::to_string(i) + " out of range");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    return makeError(where + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                     std::to_string(mesh.positions.size()) + " positions");
  }
  if (mesh.material < 0 || mesh.material >= int(materials_.size())) {
    return makeError(where + ": material " + std::to_string(mesh.material) + " out of range");
  }
  meshes_.push_back(std::move(mesh));
  topologyDirty_ = true;
  return MeshId(meshes_.size() - 1);
}

Status RtScene::updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
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
  return Ok{};
}

void RtScene::clearMeshes() {
  meshes_.clear();
  topologyDirty_ = true;
}

void RtScene::gatherTriangles() {
  triangles_.clear();
  triangleMesh_.clear();
  meshFirstTriangle_.clear();
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const RtMesh& mesh = meshes_[m];
    meshFirstTriangle_.push_back(std::uint32_t(triangles_.size()));
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      triangles_.push_back(TriangleVerts{mesh.positions[mesh.indices[i]], mesh.positions[mesh.indices[i + 1]],
                                         mesh.positions[mesh.indices[i + 2]]});
      triangleMesh_.push_back(std::uint32_t(m));
    }
  }
}

double RtScene::build() {
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles();
  bvh_.build(triangles_);
  topologyDirty_ = false;
  return secondsSince(start);
}

double RtScene::refit() {
  if (topologyDirty_) return build();
  const auto start = std::chrono::steady_clock::now();
  gatherTriangles();
  bvh_.refit(triangles_);
  return secondsSince(start);
}

template <>
const std::vector<Sphere<float>>& RtScene::spheres<float>() const {
  return spheresF_;
}
template <>
const std::vector<Sphere<double>>& RtScene::spheres<double>() const {
  return spheresD_;
}
template <>
const std::vector<Plane<float>>& RtScene::planes<float>() const {
  return planesF_;
}
template <>
const std::vector<Plane<double>>& RtScene::planes<double>() const {
  return planesD_;
}

template <typename T>
SurfaceInteraction<T> RtScene::meshInteraction(const BvhHit<T>& hit) const {
  const std::uint32_t meshIndex = triangleMesh_[hit.triangle];
  const RtMesh& mesh = meshes_[meshIndex];
  const std::size_t first = 3 * std::size_t(hit.triangle - meshFirstTriangle_[meshIndex]);
  const std::uint32_t i0 = mesh.indices[first], i1 = mesh.indices[first + 1], i2 = mesh.indices[first + 2];
  SurfaceInteraction<T> si = triangleInteraction(hit.hit, Vec3<T>(mesh.positions[i0]), Vec3<T>(mesh.positions[i1]),
                                                 Vec3<T>(mesh.positions[i2]));
  if (!mesh.normals.empty()) {
    const Vec3<T> ns = hit.hit.b0 * Vec3<T>(mesh.normals[i0]) + hit.hit.b1 * Vec3<T>(mesh.normals[i1]) +
                       hit.hit.b2 * Vec3<T>(mesh.normals[i2]);
    const T len = glm::length(ns);
    if (len > T(0)) si.ns = ns / len;
  }
  si.material = mesh.material;
  return si;
}

template <typename T>
std::optional<SurfaceInteraction<T>> RtScene::intersect(const Ray<T>& rayIn) const {
  Ray<T> ray = rayIn;
  // Which shape won: 0 none, 1 sphere, 2 plane, 3 mesh; shapes shorten tMax as they hit.
  int kind = 0;
  std::size_t index = 0;
  const auto& sphereList = spheres<T>();
  for (std::size_t i = 0; i < sphereList.size(); ++i) {
    if (auto t = sphereList[i].intersect(ray)) {
      ray.tMax = *t;
      kind = 1;
      index = i;
    }
  }
  const auto& planeList = planes<T>();
  for (std::size_t i = 0; i < planeList.size(); ++i) {
    if (auto t = planeList[i].intersect(ray)) {
      ray.tMax = *t;
      kind = 2;
      index = i;
    }
  }
  if (auto hit = bvh_.intersect(ray)) return meshInteraction(*hit);
  if (kind == 1) return sphereList[index].interaction(ray, ray.tMax);
  if (kind == 2) return planeList[index].interaction(ray, ray.tMax);
  return std::nullopt;
}

template <typename T>
bool RtScene::intersectAny(const Ray<T>& ray) const {
  for (const auto& s : spheres<T>()) {
    if (s.intersect(ray)) return true;
  }
  for (const auto& p : planes<T>()) {
    if (p.intersect(ray)) return true;
  }
  return bvh_.intersectAny(ray);
}

template std::optional<SurfaceInteraction<float>> RtScene::intersect(const Ray<float>&) const;
template std::optional<SurfaceInteraction<double>> RtScene::intersect(const Ray<double>&) const;
template bool RtScene::intersectAny(const Ray<float>&) const;
template bool RtScene::intersectAny(const Ray<double>&) const;

}  // namespace engine::rt
