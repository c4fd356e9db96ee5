#pragma once
// A bounding volume hierarchy over triangles (pbrt's BVHAggregate, reduced to what the
// ray tracer needs): built top-down with the binned surface area heuristic, stored
// flat in depth-first order (the first child follows its parent; the node holds the
// second child's index), refitted bottom-up when vertices move but the triangles stay
// the same, rebuilt when they do not.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray.h"
#include "raytrace/shapes.h"

namespace engine::rt {

struct TriangleVerts {
  glm::vec3 p0, p1, p2;
};

template <typename T>
struct BvhHit {
  TriangleIntersection<T> hit;
  std::uint32_t triangle;  // index into the span given to build()
};

class Bvh {
 public:
  // Triangles of any size, degenerate ones included (they are never hit).
  void build(std::span<const TriangleVerts> triangles);
  // The same triangles as the last build(), in the same order, at new positions.
  // The tree keeps its shape, so traversal slows as the motion grows; rebuild then.
  void refit(std::span<const TriangleVerts> triangles);

  // The nearest hit in (0, ray.tMax).
  template <typename T>
  std::optional<BvhHit<T>> intersect(const Ray<T>& ray) const;
  // Any hit in (0, ray.tMax): shadow rays stop at the first one.
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const;

  bool empty() const { return nodes_.empty(); }
  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t triangleCount() const { return triangles_.size(); }
  int depth() const { return depth_; }
  Bounds3f bounds() const { return nodes_.empty() ? Bounds3f{} : nodes_[0].bounds; }

 private:
  // The one traversal both queries use: nearest hit, or (kAnyHit) the first found.
  template <typename T, bool kAnyHit>
  std::optional<BvhHit<T>> traverse(const Ray<T>& ray) const;

  struct Node {
    Bounds3f bounds;
    std::uint32_t offset = 0;  // leaf: first triangle; interior: second child
    std::uint16_t count = 0;   // triangles in a leaf, 0 for an interior node
    std::uint8_t axis = 0;     // interior: the split axis (traversal orders by entry distance)
  };
  static_assert(sizeof(Node) == 32, "two nodes per cache line");

  struct BuildPrim {
    Bounds3f bounds;
    glm::vec3 centroid;
    std::uint32_t index;
  };

  std::uint32_t buildRecursive(std::span<BuildPrim> prims, std::uint32_t first, int depth);
  std::uint32_t makeLeaf(std::span<BuildPrim> prims, std::uint32_t first);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;         // leaf order -> index given to build()
  std::vector<TriangleVerts> triangles_;     // in leaf order, for traversal
  int depth_ = 0;
};

}  // namespace engine::rt
