#pragma once
// The ray tracer's acceleration structure: the analytic spheres and planes (in both
// precisions, and packed four and eight to a test for float rays) and the triangle
// meshes in world space in BVH groups, and the queries over all of them (nearest hit,
// any hit, batches and packets of rays). RtScene (rt_scene.h) composes it with the
// materials and lights.
//
// Two levels: meshes belong to groups, each group has its own BVH, and a ray visits
// every group whose bounds it crosses. Group 0 holds the static world (boxes, the
// 1.3M-triangle terrain), built once; each character gets a group of its own, so a
// new pose refits that character's BVH (its vertices move, its triangles stay) and
// never touches the terrain's. A linear top level suits the few groups a scene has
// (the demo: 5); hundreds of instances would want a BVH over the groups.
//
// A hit record's texture coordinates are worked out only where its material reads
// them, and a triangle's uv gradient only where its material is anisotropic: the
// queries that make hit records take the material table (rt_materials.h) to ask.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "raytrace/avx2_region.h"
#include "raytrace/bvh.h"
#include "raytrace/ray.h"
#include "raytrace/rt_materials.h"
#include "raytrace/shape_lanes.h"
#include "raytrace/shape_packs.h"
#include "raytrace/shapes.h"

namespace engine::rt {

// A triangle mesh in world space. Normals are optional (empty: flat shading from the
// triangle's own normal); when present there is one per position.
struct RtMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;  // empty, or one per position (glTF TEXCOORD_0)
  std::vector<glm::vec2> uvs1;  // empty (hits take uvs), or one per position (TEXCOORD_1)
  std::vector<glm::vec4> colors;  // empty (white), or one per position (COLOR_0, linear RGBA)
  std::vector<std::uint32_t> indices;  // three per triangle
  int material = 0;
  int group = 0;  // the BVH it lives in: 0 the static world, or one from addGroup()
};

using MeshId = int;

class RtAccel {
 public:
  void addSphere(const glm::dvec3& center, double radius, int material);
  // `extent`: the half size of the square the rasterizer draws; hits beyond it miss,
  // and it sets the plane's texture coordinates. 0: an unbounded plane.
  void addPlane(const glm::dvec3& point, const glm::dvec3& normal, int material, double extent = 0.0);

  // A new, empty BVH group for meshes that move together (one character), or that
  // rays meet apart from the rest (raytrace/ground_split.h). `name`: what --describe
  // calls it.
  int addGroup(std::string name = {});
  // Group 0 is "static".
  std::string groupName(int group) const { return group == 0 ? "static" : groups_[std::size_t(group)].name; }
  // Validates the mesh (indices in range, one normal per position, a material below
  // `materialCount` and a known group); its group's BVH is rebuilt at the next
  // build() or refit().
  Result<MeshId> addMesh(RtMesh mesh, int materialCount);
  // New vertex positions (and normals, if the mesh has them) for the same triangles.
  Status updateMesh(MeshId id, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals = {});
  void clearMeshes();

  // Rebuilds every group's BVH with the SAH; returns the seconds it took.
  double build();
  // Refits the BVH of each group whose meshes moved (updateMesh) and builds those
  // that gained meshes since their last build; returns the seconds it took.
  double refit();
  // The same for one group (the per-character figures of the benchmark).
  double buildGroup(int group);
  double refitGroup(int group);

  // The nearest hit in (0, ray.tMax) over every shape, and whether any hit exists;
  // `materials` says which hits need texture coordinates.
  template <typename T>
  std::optional<SurfaceInteraction<T>> intersect(const Ray<T>& ray, const RtMaterials& materials) const;
  // intersect() of each of several float rays (a batch of paths, a bounce at a time),
  // the same answers bit for bit; the spheres and planes meet four or eight rays at a
  // time.
  void intersectMany(const Ray<float>* const* rays, std::size_t count, std::optional<SurfaceInteraction<float>>* out,
                     const RtMaterials& materials) const;
  // intersect() of eight coherent float rays (a camera's row of eight pixels): each
  // ray's spheres and planes on its own, then each group's BVH for the rays that enter
  // its box, together (Bvh::intersect8). The same nearest hits bit for bit, but that
  // of triangles at exactly the same distance either may be named, and that a
  // triangle an ulp or two before the nearest hit so far, behind a box whose entry the
  // ray alone rounds to that hit's distance, may be found (the packet's interval box
  // test enters it): a crate's floor on the plaza, from inside the crate.
  void intersectCoherent(std::span<const Ray<float>, Bvh::kPacketSize> rays,
                         std::span<std::optional<SurfaceInteraction<float>>, Bvh::kPacketSize> out,
                         const RtMaterials& materials) const;
  // Whether intersectMany takes eight rays to a pass (no triangles, and AVX2) rather
  // than four.
  bool eightRaysAtATime() const { return !boxedTriangles_ && lanes_.size() > 0 && cpuHasAvx2(); }
  // Whether anything lies in (0, ray.tMax).
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const;

  const std::vector<RtMesh>& meshes() const { return meshes_; }
  int groupCount() const { return int(groups_.size()); }
  const Bvh& bvh(int group = 0) const { return groups_[std::size_t(group)].bvh; }
  std::size_t triangleCount() const;
  // What gputrace/gpu_layout.h flattens for the GPU: the float shapes, each plane's
  // square (onPlaneSquare), and which mesh each of a group's triangles comes from
  // (the BVH's triangle index is its place in its group, meshes in group order).
  const std::vector<Sphere<float>>& floatSpheres() const { return spheresF_; }
  const std::vector<Plane<float>>& floatPlanes() const { return planesF_; }
  const PlaneSquare& planeSquare(std::size_t plane) const { return planeUvs_[plane]; }
  const std::vector<std::uint32_t>& groupTriangleMeshes(int group) const {
    return groups_[std::size_t(group)].triangleMesh;
  }
  std::uint32_t meshFirstTriangle(MeshId mesh) const { return meshFirstTriangle_[std::size_t(mesh)]; }
  std::size_t sphereCount() const { return spheresF_.size(); }
  // The spheres and planes as the eight-lane kernels read them (shape_lanes.h).
  const ShapeLanes& shapeLanes() const { return lanes_; }
  std::size_t planeCount() const { return planesF_.size(); }

 private:
  template <typename T>
  const std::vector<Sphere<T>>& spheres() const;
  template <typename T>
  const std::vector<Plane<T>>& planes() const;
  struct Group;
  template <typename T>
  SurfaceInteraction<T> meshInteraction(const Group& group, const BvhHit<T>& hit, const RtMaterials& materials) const;
  template <typename T>
  bool onPlaneSquare(std::size_t plane, const Ray<T>& ray, T t) const;
  // The nearest sphere and plane hits (kind 1 or 2, or 0) with ray.tMax shortened to
  // them, and whether any exists: four shapes at a time for float rays, one at a time
  // for double.
  // `testSpheres` false: the ray misses every sphere (RootHits::spheres), none is tested.
  template <typename T>
  int nearestShape(Ray<T>& ray, std::size_t& index, bool testSpheres = true) const;
  template <typename T>
  bool anyShape(const Ray<T>& ray, bool testSpheres = true) const;
  // nearestShape of eight float rays at once, a ray to a lane (lanes8::Shapes::nearest,
  // the same bits; every sphere tested, since the spheres' root box only ever skips
  // spheres a ray misses). AVX2 only.
  void nearestShapesOfEight(Ray<float>* rays, int* kind, std::size_t* index) const;
  // The groups' root boxes and the spheres' box side by side as one 8-wide BVH node,
  // tested once per float ray (Bvh::testBoxes, all at once) in place of a scalar box
  // test per group, and so that rays that miss every sphere test none: lane g is
  // group g's root box, the last lane a box around the spheres, widened so that every
  // hit the float sphere test finds lies within it. Used when there are at most seven
  // groups; remade whenever a group's tree or the spheres change.
  static constexpr int kSphereLane = Bvh::kWidth - 1;
  struct RootHits {
    int mask = 0;
    alignas(32) float tEntry[Bvh::kWidth];
    // Group g's box entered before tMax: the scalar intersectBounds' answer.
    bool group(std::size_t g, float tMax) const { return (mask >> g & 1) && tEntry[g] < tMax; }
    bool spheres() const { return (mask >> kSphereLane & 1) != 0; }
  };
  bool rootsUsable() const { return groups_.size() <= std::size_t(kSphereLane); }
  RootHits testRoots(const Ray<float>& ray) const;
  // The same into `hits` in place (an array's element: assigning one returned read
  // it back in 16-byte loads over the mask's 4-byte store, a store-forwarding stall).
  void testRoots(const Ray<float>& ray, RootHits& hits) const;
  void updateRoots();
  // intersect() once the spheres and planes have shortened ray.tMax to their nearest
  // (kind 1 or 2 at `index`, 0 none): the meshes, then the winner's interaction,
  // written into `result` where it is kept (a record returned was copied). `roots`:
  // the ray's RootHits at its tMax before the shapes, when the caller has them.
  template <typename T>
  void pastShapes(Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result,
                  const RtMaterials& materials, const RootHits* roots = nullptr) const;
  // The hit record of the sphere (kind 1) or plane (2) at `index` that `ray` meets at
  // ray.tMax; nothing for kind 0.
  template <typename T>
  void shapeInteraction(const Ray<T>& ray, int kind, std::size_t index, std::optional<SurfaceInteraction<T>>& result,
                        const RtMaterials& materials) const;
  // The rest of a sphere's (kind 1) or plane's (2) hit record once fillInteraction has
  // made it: texture coordinates where its material reads them, their scale per metre.
  template <typename T>
  void shapeUv(int kind, std::size_t index, SurfaceInteraction<T>& si, const RtMaterials& materials) const;
  // intersectMany of up to eight rays in a scene without triangles, in one AVX2 pass
  // over the shapes (shape_lanes.h).
  void intersectEight(const Ray<float>* const* rays, int count, std::optional<SurfaceInteraction<float>>* out,
                      const RtMaterials& materials) const;
  // onPlaneSquare as ShapePacks asks it.
  static bool onSquareOf(const void* accel, std::size_t plane, const Ray<float>& ray, float t);
  void gatherTriangles(int group);

  // Per plane, its square and what its texture coordinates need: the rasterizer
  // draws it as a square of half size `extent` (0: unbounded) rotated from +y to its
  // normal, with uv = (local + extent) * texture scale along that square's x and z.
  using PlaneUv = PlaneSquare;
  std::vector<PlaneUv> planeUvs_;

  // Each analytic shape in both precisions, so neither path converts per ray.
  std::vector<Sphere<float>> spheresF_;
  std::vector<Sphere<double>> spheresD_;
  std::vector<Plane<float>> planesF_;
  std::vector<Plane<double>> planesD_;
  // The float shapes again, four to a pack, for float rays (shape_packs.h), and as
  // one table for eight rays at once (shape_lanes.h).
  ShapePacks packs_;
  ShapeLanes lanes_;

  struct Group {
    std::string name;
    std::vector<std::uint32_t> meshes;
    std::vector<TriangleVerts> triangles;     // its meshes' triangles, in mesh order
    std::vector<std::uint32_t> triangleMesh;  // triangle -> mesh
    Bvh bvh;
    bool topologyDirty = false;  // meshes added since the last build
    bool moved = false;          // vertices updated since the last build or refit
  };

  std::vector<RtMesh> meshes_;
  std::vector<std::uint32_t> meshFirstTriangle_;  // into its group's triangles
  std::vector<Group> groups_{1};
  // Whether any group's BVH holds a triangle: group 0 is always there, empty in a
  // scene of spheres and planes, whose rays then skip the groups' boxes altogether.
  bool boxedTriangles_ = false;
  // See RootHits. Rays from beyond rootsOriginLimit_ (16 times the farthest box
  // coordinate) test the spheres regardless: the box's margin is sized for rays from
  // within it. Empty boxes until updateRoots.
  Bvh::Node roots_ = noRoots();
  float rootsOriginLimit_ = -1.0f;
  static Bvh::Node noRoots();
};

}  // namespace engine::rt
