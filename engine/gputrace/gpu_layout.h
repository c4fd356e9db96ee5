#pragma once
// The CPU tracer's scene as flat arrays for a GPU traversal (shaders/rt/), GL-free:
// the very BVH8 the CPU built, not a second tree. Each group's nodes, Triangle4
// leaves and leaf-slot -> triangle table are concatenated, their child references
// rebased into the shared arrays; a group becomes an instance (its root reference
// and bounds, tested first as RtScene::intersect does). Triangles get one global id,
// group by group in BVH order (a group's triangle i is first(group) + i). The structs
// are std430 layouts, written to shader storage buffers as they are.
//
// Two widths, both from the CPU's tree. Eight, as the CPU has it: a node is 12 vec4
// loads of boxes (two halves of four children per slab row) and one test of eight
// children, over a tree a third as deep as a BVH2. Four: each CPU node of more than
// four children becomes a 4-wide node whose first slots hold pairs of adjacent
// children (siblings in the builder's binary tree, as the collapse keeps its
// left-to-right order) under their joint box; half the loads per node, up to twice
// the levels. Measured on llvmpipe (bench/gpu_trace, docs/bench-log/gpu-tracer.md),
// the 4-wide tree traces twice as fast: the GPU tracer's default. Not profiled; the
// likely cost of 8 wide there is the sort of up to eight hits per node into a stack
// of seven entries a level, private arrays that llvmpipe keeps in memory.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/rt_scene.h"

namespace engine::rt {

struct GpuNode {
  // box[2 * row + half]: Bvh::Node::box[row] (min x, y, z, max x, y, z) for
  // children 4 * half .. 4 * half + 3.
  glm::vec4 box[12];
  glm::uvec4 child[2];  // Bvh references (leaf bit, count, block), rebased
};
static_assert(sizeof(GpuNode) == 224);

// The 4-wide node: box[row] for children 0-3.
struct GpuNode4 {
  glm::vec4 box[6];
  glm::uvec4 child;
};
static_assert(sizeof(GpuNode4) == 112);

struct GpuLeaf {
  glm::vec4 p[9];  // p[3 * vertex + axis][lane]: Bvh::Triangle4 as it is
};
static_assert(sizeof(GpuLeaf) == 144);

struct GpuInstance {
  glm::vec4 boundsMin;  // the group's BVH bounds
  glm::vec4 boundsMax;
  glm::uvec4 root;      // x: the root reference, rebased
};

struct GpuSphere {
  glm::vec4 centerRadius;
  glm::ivec4 material;  // x
};

struct GpuPlane {
  glm::vec4 normalD;      // dot(normal, p) = d
  glm::vec4 pointExtent;  // the square the rasterizer draws: centre, half size (0: unbounded)
  glm::vec4 axisU;        // xyz; w: the material, as a float
  glm::vec4 axisV;
};

// What shading a triangle hit needs beyond the leaf's positions.
struct GpuTriangle {
  glm::vec4 n[3];  // vertex normals; n[0].w the material, n[1].w 1 when the mesh has normals, n[2].w when colours
};

struct GpuSceneLayout {
  int width = 8;  // 8: nodes holds the tree; 4: nodes4 does
  std::vector<GpuNode> nodes;
  std::vector<GpuNode4> nodes4;
  std::vector<GpuLeaf> leaves;
  std::vector<std::uint32_t> order;  // 4 per leaf: the lane's global triangle id, or Bvh::kNoChild
  std::vector<GpuInstance> instances;
  std::vector<GpuSphere> spheres;
  std::vector<GpuPlane> planes;
  std::vector<GpuTriangle> triangles;  // by global id
  // What shading reads of a triangle beyond its normals, attributeSlots() vec4 a
  // triangle by global id: where hasUvs, each vertex's uv sets (TEXCOORD_0 in xy,
  // TEXCOORD_1 in zw: TEXCOORD_0 again where the mesh has no second set, zero where
  // it has none); then, where hasColors, each vertex's COLOR_0 (linear RGBA).
  std::vector<glm::vec4> triangleAttributes;
  std::vector<std::uint32_t> firstTriangle;  // per group: its first global id
  bool hasColors = false;  // some mesh has vertex colours
  bool hasUvs = false;     // some material reads a texture or is anisotropic, and some mesh has uvs
  int attributeSlots() const { return 3 * (int(hasUvs) + int(hasColors)); }
  int depth = 0;  // levels of nodes on the deepest path, leaves included

  // The most entries a traversal stack holds: width - 1 per level (Bvh::kStackSize's rule).
  int stackSize() const { return (width - 1) * depth + 1; }
};

// The scene's groups (already built) and analytic shapes, flattened; `width` 8 or 4.
GpuSceneLayout flattenScene(const RtScene& scene, int width = 8);

// What refitting one group in place on the GPU takes (gputrace/gpu_refit.h), given the
// group's vertices in one array: its meshes' vertices one mesh after another, in the
// order the group's triangles list them. Indices below are into that array.
struct GpuRefitPlan {
  int instance = -1;  // the group's GpuInstance; -1 when its BVH is empty
  std::uint32_t firstLeaf = 0;
  std::vector<glm::uvec4> leafCorners;  // 4 per leaf: the lane's three vertices, w 1 (0: an empty lane)
  std::uint32_t firstTriangle = 0;
  std::vector<glm::uvec4> triangleCorners;  // per triangle (global id order): its vertices, w 1 when the mesh has normals
  // The group's nodes (indices into nodes or nodes4) by depth, deepest first: a
  // level's boxes are made from the level below it.
  std::vector<std::vector<std::uint32_t>> levels;
  std::uint32_t vertexCount = 0;
};
GpuRefitPlan refitPlan(const RtScene& scene, const GpuSceneLayout& layout, int group);

}  // namespace engine::rt
