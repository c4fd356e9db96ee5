#include "raytrace/bvh.h"

#include <algorithm>
#include <array>

namespace engine::rt {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafTriangles = 4;
// SAH costs relative to one triangle test (pbrt's 1/8 for a node visit would give
// deeper trees; a half keeps leaves of 2-4 triangles, faster for our small meshes).
constexpr float kTraversalCost = 0.5f;
// Past this depth splits are by object median, so the traversal stack (64) cannot
// overflow whatever the triangles look like.
constexpr int kMaxSahDepth = 48;
constexpr int kStackSize = 64;

Bounds3f triangleBounds(const TriangleVerts& t) {
  Bounds3f b;
  b.extend(t.p0);
  b.extend(t.p1);
  b.extend(t.p2);
  return b;
}

struct Bin {
  Bounds3f bounds;
  std::uint32_t count = 0;
};

struct Split {
  int axis = -1;
  int bin = 0;  // primitives in bins [0, bin] go left
  float cost = 0.0f;
};

int binIndex(float c, float lo, float extent) {
  const int b = int(kBins * ((c - lo) / extent));
  return std::clamp(b, 0, kBins - 1);
}

}  // namespace

std::uint32_t Bvh::makeLeaf(std::span<BuildPrim> prims, std::uint32_t first) {
  Node node;
  node.offset = first;
  node.count = std::uint16_t(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    node.bounds.extend(prims[i].bounds);
    order_[first + i] = prims[i].index;
  }
  nodes_.push_back(node);
  return std::uint32_t(nodes_.size() - 1);
}

std::uint32_t Bvh::buildRecursive(std::span<BuildPrim> prims, std::uint32_t first, int depth) {
  depth_ = std::max(depth_, depth + 1);
  Bounds3f bounds, centroids;
  for (const BuildPrim& p : prims) {
    bounds.extend(p.bounds);
    centroids.extend(p.centroid);
  }
  const std::size_t n = prims.size();
  if (n <= 1) return makeLeaf(prims, first);

  const int axis = centroids.maxExtentAxis();
  const float lo = centroids.min[axis];
  const float extent = centroids.max[axis] - lo;
  std::size_t mid = n / 2;
  bool split = false;
  if (extent > 0.0f && depth < kMaxSahDepth) {
    std::array<Bin, kBins> bins{};
    for (const BuildPrim& p : prims) {
      Bin& b = bins[binIndex(p.centroid[axis], lo, extent)];
      ++b.count;
      b.bounds.extend(p.bounds);
    }
    // Sweep from the right to get each suffix's area and count, then from the left.
    std::array<float, kBins> rightArea{};
    std::array<std::uint32_t, kBins> rightCount{};
    Bounds3f acc;
    std::uint32_t count = 0;
    for (int i = kBins - 1; i > 0; --i) {
      acc.extend(bins[i].bounds);
      count += bins[i].count;
      rightArea[i] = acc.surfaceArea();
      rightCount[i] = count;
    }
    Split best;
    acc = Bounds3f{};
    count = 0;
    for (int i = 0; i < kBins - 1; ++i) {
      acc.extend(bins[i].bounds);
      count += bins[i].count;
      if (count == 0 || rightCount[i + 1] == 0) continue;
      const float cost = acc.surfaceArea() * float(count) + rightArea[i + 1] * float(rightCount[i + 1]);
      if (best.axis < 0 || cost < best.cost) best = Split{axis, i, cost};
    }
    const float area = bounds.surfaceArea();
    const float splitCost = kTraversalCost + (area > 0.0f ? best.cost / area : 0.0f);
    const float leafCost = float(n);
    if (best.axis < 0 || (n <= kMaxLeafTriangles && leafCost <= splitCost)) {
      if (n <= kMaxLeafTriangles) return makeLeaf(prims, first);
    } else {
      auto it = std::partition(prims.begin(), prims.end(), [&](const BuildPrim& p) {
        return binIndex(p.centroid[axis], lo, extent) <= best.bin;
      });
      mid = std::size_t(it - prims.begin());
      split = mid > 0 && mid < n;
    }
  } else if (n <= kMaxLeafTriangles) {
    return makeLeaf(prims, first);
  }
  if (!split) {
    // Coincident centroids, too deep, or no useful SAH split: the object median.
    mid = n / 2;
    std::nth_element(prims.begin(), prims.begin() + std::ptrdiff_t(mid), prims.end(),
                     [&](const BuildPrim& a, const BuildPrim& b) { return a.centroid[axis] < b.centroid[axis]; });
  }

  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  buildRecursive(prims.subspan(0, mid), first, depth + 1);
  const std::uint32_t second = buildRecursive(prims.subspan(mid), first + std::uint32_t(mid), depth + 1);
  Node& node = nodes_[index];
  node.bounds = bounds;
  node.offset = second;
  node.count = 0;
  node.axis = std::uint8_t(axis);
  return index;
}

void Bvh::build(std::span<const TriangleVerts> triangles) {
  nodes_.clear();
  depth_ = 0;
  order_.assign(triangles.size(), 0);
  triangles_.clear();
  if (triangles.empty()) return;
  std::vector<BuildPrim> prims(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    prims[i].bounds = triangleBounds(triangles[i]);
    prims[i].centroid = prims[i].bounds.centroid();
    prims[i].index = std::uint32_t(i);
  }
  nodes_.reserve(2 * triangles.size());
  buildRecursive(prims, 0, 0);
  triangles_.resize(triangles.size());
  for (std::size_t i = 0; i < order_.size(); ++i) triangles_[i] = triangles[order_[i]];
}

void Bvh::refit(std::span<const TriangleVerts> triangles) {
  for (std::size_t i = 0; i < order_.size(); ++i) triangles_[i] = triangles[order_[i]];
  // Children follow their parents, so a reverse sweep sees both children first.
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& node = nodes_[i];
    Bounds3f b;
    if (node.count > 0) {
      for (std::uint32_t k = 0; k < node.count; ++k) b.extend(triangleBounds(triangles_[node.offset + k]));
    } else {
      b = nodes_[i + 1].bounds;
      b.extend(nodes_[node.offset].bounds);
    }
    node.bounds = b;
  }
}

namespace {

template <typename T>
Vec3<T> toT(const glm::vec3& v) {
  return Vec3<T>(v);
}

}  // namespace

// Children are tested from their parent: both boxes, then the nearer entered first
// and the farther pushed with its entry distance, which is checked again when it is
// popped (a nearest hit found meanwhile skips it without touching the node). The
// per-ray part of the triangle test is computed once.
template <typename T, bool kAnyHit>
std::optional<BvhHit<T>> Bvh::traverse(const Ray<T>& rayIn) const {
  if (nodes_.empty()) return std::nullopt;
  Ray<T> ray = rayIn;
  const Vec3<T> invDir = T(1) / ray.d;
  const int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
  const TriangleRay<T> triRay(ray);
  std::optional<BvhHit<T>> best;
  struct Entry {
    std::uint32_t node;
    T tEntry;
  };
  Entry stack[kStackSize];
  int top = 0;
  T tRoot = 0;
  if (!intersectBounds(nodes_[0].bounds, ray, ray.tMax, invDir, dirIsNeg, tRoot)) return std::nullopt;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      for (std::uint32_t k = 0; k < node.count; ++k) {
        const TriangleVerts& tri = triangles_[node.offset + k];
        if (auto hit = intersectTriangle(triRay, ray.tMax, toT<T>(tri.p0), toT<T>(tri.p1), toT<T>(tri.p2))) {
          best = BvhHit<T>{*hit, order_[node.offset + k]};
          if constexpr (kAnyHit) return best;
          ray.tMax = hit->t;
        }
      }
    } else {
      const std::uint32_t first = current + 1, second = node.offset;
      T t0 = 0, t1 = 0;
      const bool hit0 = intersectBounds(nodes_[first].bounds, ray, ray.tMax, invDir, dirIsNeg, t0);
      const bool hit1 = intersectBounds(nodes_[second].bounds, ray, ray.tMax, invDir, dirIsNeg, t1);
      if (hit0 && hit1) {
        const bool firstNearer = t0 <= t1;
        stack[top++] = firstNearer ? Entry{second, t1} : Entry{first, t0};
        current = firstNearer ? first : second;
        continue;
      }
      if (hit0 || hit1) {
        current = hit0 ? first : second;
        continue;
      }
    }
    // Pop the next box the ray still enters before its nearest hit.
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.tEntry < ray.tMax) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  return best;
}

template <typename T>
std::optional<BvhHit<T>> Bvh::intersect(const Ray<T>& ray) const {
  return traverse<T, false>(ray);
}

template <typename T>
bool Bvh::intersectAny(const Ray<T>& ray) const {
  return traverse<T, true>(ray).has_value();
}

template std::optional<BvhHit<float>> Bvh::intersect(const Ray<float>&) const;
template std::optional<BvhHit<double>> Bvh::intersect(const Ray<double>&) const;
template bool Bvh::intersectAny(const Ray<float>&) const;
template bool Bvh::intersectAny(const Ray<double>&) const;

}  // namespace engine::rt
