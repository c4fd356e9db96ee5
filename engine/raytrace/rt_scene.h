#pragma once
// What the ray tracer traces: analytic spheres and planes, triangle meshes in world
// space under one BVH, lights, materials, camera and sky. Built from the SceneDesc the
// rasterizer also reads; the caller adds meshes (skinned characters, terrain) and, per
// frame, moves their vertices and calls refit() (or build() when triangles change).
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "asset/scene_desc.h"
#include "core/result.h"
#include "raytrace/bvh.h"
#include "raytrace/ray.h"
#include "raytrace/shapes.h"

namespace engine::rt {

// A triangle mesh in world space. Normals are optional (empty: flat shading from the
// triangle's own normal); when present there is one per position.
struct RtMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;  // three per triangle
  int material = 0;
};

using MeshId = int;

class RtScene {
 public:
  RtScene();  // one default material, no shapes, no lights, the default camera
  // Spheres, planes, boxes (as 12 triangles each), lights, materials, camera, sky and
  // render settings. Models and terrain are the caller's to add as meshes.
  static Result<RtScene> fromSceneDesc(const SceneDesc& desc);

  int addMaterial(const MaterialDesc& material);
  void addLight(const LightDesc& light) { lights_.push_back(light); }
  void addSphere(const glm::dvec3& center, double radius, int material);
  void addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material);
  void setCamera(const CameraDesc& camera) { camera_ = camera; }
  void setSky(const SkyDesc& sky) { sky_ = sky; }
  void setRender(const RenderDesc& render) { render_ = render; }

  // Validates the mesh (indices in range, one normal per position, a known material);
  // the BVH is rebuilt at the next build() (or refit(), which then builds).
  Result<MeshId> addMesh(RtMesh mesh);
  // New vertex positions (and normals, if the mesh has them) for the same triangles.
  Status updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals = {});
  void clearMeshes();

  // Rebuilds the BVH over every mesh with the SAH; returns the seconds it took.
  double build();
  // Refits the BVH to moved vertices (builds instead if meshes were added or removed
  // since the last build); returns the seconds it took.
  double refit();

  // The nearest hit in (0, ray.tMax) over every shape, and whether any hit exists.
  template <typename T>
  std::optional<SurfaceInteraction<T>> intersect(const Ray<T>& ray) const;
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const;

  const CameraDesc& camera() const { return camera_; }
  const std::vector<LightDesc>& lights() const { return lights_; }
  const std::vector<MaterialDesc>& materials() const { return materials_; }
  const SkyDesc& sky() const { return sky_; }
  // PBR's hemisphere ambient (see ambientSkyColor in asset/scene_desc.h).
  glm::vec3 ambientSky() const { return ambientSky_; }
  glm::vec3 ambientGround() const { return ambientGround_; }
  const RenderDesc& render() const { return render_; }
  const std::vector<RtMesh>& meshes() const { return meshes_; }
  const Bvh& bvh() const { return bvh_; }
  std::size_t triangleCount() const { return triangles_.size(); }
  std::size_t sphereCount() const { return spheresF_.size(); }
  std::size_t planeCount() const { return planesF_.size(); }

 private:
  template <typename T>
  const std::vector<Sphere<T>>& spheres() const;
  template <typename T>
  const std::vector<Plane<T>>& planes() const;
  template <typename T>
  SurfaceInteraction<T> meshInteraction(const BvhHit<T>& hit) const;
  void gatherTriangles();

  CameraDesc camera_;
  std::vector<LightDesc> lights_;
  std::vector<MaterialDesc> materials_;
  SkyDesc sky_;
  glm::vec3 ambientSky_{0.1f};
  glm::vec3 ambientGround_{0.1f};
  RenderDesc render_;
  // Each analytic shape in both precisions, so neither path converts per ray.
  std::vector<Sphere<float>> spheresF_;
  std::vector<Sphere<double>> spheresD_;
  std::vector<Plane<float>> planesF_;
  std::vector<Plane<double>> planesD_;

  std::vector<RtMesh> meshes_;
  std::vector<TriangleVerts> triangles_;       // every mesh's triangles, in mesh order
  std::vector<std::uint32_t> triangleMesh_;    // triangle -> mesh
  std::vector<std::uint32_t> meshFirstTriangle_;
  bool topologyDirty_ = false;
  Bvh bvh_;
};

}  // namespace engine::rt
