#include "raytrace/bvh.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <limits>

#include <immintrin.h>

namespace engine::rt {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafTriangles = 4;  // a leaf reference holds 1-4
// SAH costs relative to one triangle test (pbrt's 1/8 for a node visit would give
// deeper trees; a half keeps leaves of 2-4 triangles, faster for our small meshes).
constexpr float kTraversalCost = 0.5f;
constexpr int kMaxSahDepth = 48;
// Past this depth splits are by object median, so the traversal stack cannot overflow
// whatever the triangles look like: at most three children pushed per level.
constexpr int kStackSize = 3 * 64 + 1;

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
  BinaryNode node;
  node.offset = first;
  node.count = std::uint16_t(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    node.bounds.extend(prims[i].bounds);
    order_[first + i] = prims[i].index;
  }
  binary_.push_back(node);
  return std::uint32_t(binary_.size() - 1);
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

  const std::uint32_t index = std::uint32_t(binary_.size());
  binary_.push_back(BinaryNode{});
  buildRecursive(prims.subspan(0, mid), first, depth + 1);
  const std::uint32_t second = buildRecursive(prims.subspan(mid), first + std::uint32_t(mid), depth + 1);
  BinaryNode& node = binary_[index];
  node.bounds = bounds;
  node.offset = second;
  node.count = 0;
  return index;
}

// Gathers up to four descendants of a binary interior node, opening the largest
// interior one each time (its children are the likeliest to be visited), and makes
// them one Node4; interior ones are collapsed in turn, after their parent.
std::uint32_t Bvh::collapse(std::uint32_t binary) {
  std::array<std::uint32_t, 4> kids{binary + 1, binary_[binary].offset, 0, 0};
  int n = 2;
  while (n < 4) {
    int open = -1;
    float area = -1.0f;
    for (int i = 0; i < n; ++i) {
      const BinaryNode& kid = binary_[kids[i]];
      if (kid.count == 0 && kid.bounds.surfaceArea() > area) {
        open = i;
        area = kid.bounds.surfaceArea();
      }
    }
    if (open < 0) break;
    const std::uint32_t opened = kids[open];
    // The second child goes right after the first, keeping the tree's left-to-right order.
    for (int i = n; i > open + 1; --i) kids[i] = kids[i - 1];
    kids[open] = opened + 1;
    kids[open + 1] = binary_[opened].offset;
    ++n;
  }
  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.push_back(Node4{});
  for (int i = 0; i < 4; ++i) {
    const Bounds3f b = i < n ? binary_[kids[i]].bounds : Bounds3f{};
    const std::uint32_t child = i < n ? reference(kids[i]) : kNoChild;
    Node4& node = nodes_[index];  // reference() may have moved the vector
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][i] = b.min[axis];
      node.box[3 + axis][i] = b.max[axis];
    }
    node.child[i] = child;
  }
  return index;
}

// A binary node as a Node4 child: a leaf's triangles, or the interior node collapsed.
std::uint32_t Bvh::reference(std::uint32_t binary) {
  const BinaryNode& node = binary_[binary];
  return node.count > 0 ? leafRef(node.offset, node.count) : collapse(binary);
}

void Bvh::build(std::span<const TriangleVerts> triangles) {
  if (triangles.size() >= kMaxTriangles) throw std::length_error("Bvh::build: 2^28 triangles or more");
  nodes_.clear();
  binary_.clear();
  rootBounds_ = Bounds3f{};
  root_ = kNoChild;
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
  binary_.reserve(2 * triangles.size());
  buildRecursive(prims, 0, 0);
  triangles_.resize(triangles.size());
  for (std::size_t i = 0; i < order_.size(); ++i) triangles_[i] = triangles[order_[i]];

  rootBounds_ = binary_[0].bounds;
  nodes_.reserve(binary_.size() / 6 + 1);  // about a third of the interior nodes
  root_ = reference(0);
  binary_ = {};  // the traversal reads only the Node4s
}

// A node's boxes from its children: leaves from their triangles, interior nodes from
// their own (already refitted) boxes.
Bounds3f Bvh::childBounds(std::uint32_t ref) const {
  Bounds3f b;
  if (isLeaf(ref)) {
    const std::uint32_t first = leafFirst(ref);
    for (std::uint32_t k = first; k < first + leafCount(ref); ++k) b.extend(triangleBounds(triangles_[k]));
  } else {
    const Node4& kid = nodes_[ref];
    for (int j = 0; j < 4; ++j) {
      b.extend(glm::vec3(kid.box[0][j], kid.box[1][j], kid.box[2][j]));
      b.extend(glm::vec3(kid.box[3][j], kid.box[4][j], kid.box[5][j]));
    }
  }
  return b;
}

void Bvh::refitNode(std::uint32_t index) {
  Node4& node = nodes_[index];
  for (int i = 0; i < 4; ++i) {
    if (node.child[i] == kNoChild) continue;
    const Bounds3f b = childBounds(node.child[i]);
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][i] = b.min[axis];
      node.box[3 + axis][i] = b.max[axis];
    }
  }
}

void Bvh::refit(std::span<const TriangleVerts> triangles) {
  for (std::size_t i = 0; i < order_.size(); ++i) triangles_[i] = triangles[order_[i]];
  if (triangles_.empty()) return;
  // Children follow their parents, so a reverse sweep refits children first.
  for (std::size_t i = nodes_.size(); i-- > 0;) refitNode(std::uint32_t(i));
  rootBounds_ = childBounds(root_);
}

namespace {

template <typename T>
Vec3<T> toT(const glm::vec3& v) {
  return Vec3<T>(v);
}

// The per-ray part of the box test: the ray's origin and inverse direction, and
// which of a Node4's six rows is each axis' near and far slab. Any precision:
// intersectBounds on each child box in turn.
template <typename T>
class ChildBoxTest {
 public:
  explicit ChildBoxTest(const Ray<T>& ray) : ray_(ray), invDir_(T(1) / ray.d) {
    for (int axis = 0; axis < 3; ++axis) dirIsNeg_[axis] = invDir_[axis] < 0;
  }

  bool root(const Bounds3f& b, T& tEntry) const {
    return intersectBounds(b, ray_, ray_.tMax, invDir_, dirIsNeg_, tEntry);
  }

  // The mask of the children hit before tMax, and their entry distances.
  template <typename Node>
  int operator()(const Node& node, T tMax, T tEntry[4]) const {
    int mask = 0;
    for (int i = 0; i < 4; ++i) {
      Bounds3f b;
      b.min = glm::vec3(node.box[0][i], node.box[1][i], node.box[2][i]);
      b.max = glm::vec3(node.box[3][i], node.box[4][i], node.box[5][i]);
      if (intersectBounds(b, ray_, tMax, invDir_, dirIsNeg_, tEntry[i])) mask |= 1 << i;
    }
    return mask;
  }

 private:
  Ray<T> ray_;
  Vec3<T> invDir_;
  int dirIsNeg_[3];
};

// Float rays: the same test on all four boxes at once (SSE, part of every x86-64),
// with the ray's values broadcast once per ray. Written to give intersectBounds'
// answers bit for bit: _mm_max_ps and _mm_min_ps return their second operand when
// either is NaN, which drops an axis whose slab the ray lies in exactly as the scalar
// test's comparisons do (x: the NaN becomes the unbounded start value).
template <>
class ChildBoxTest<float> {
 public:
  explicit ChildBoxTest(const Ray<float>& ray) : ray_(ray), invDir_(1.0f / ray.d) {
    for (int axis = 0; axis < 3; ++axis) {
      const int neg = invDir_[axis] < 0;
      dirIsNeg_[axis] = neg;
      nearRow_[axis] = axis + 3 * neg;
      farRow_[axis] = axis + 3 * (1 - neg);
      o_[axis] = _mm_set1_ps(ray.o[axis]);
      inv_[axis] = _mm_set1_ps(invDir_[axis]);
    }
  }

  bool root(const Bounds3f& b, float& tEntry) const {
    return intersectBounds(b, ray_, ray_.tMax, invDir_, dirIsNeg_, tEntry);
  }

  template <typename Node>
  [[gnu::always_inline]] int operator()(const Node& node, float tMax, float tEntry[4]) const {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const __m128 widen = _mm_set1_ps(1.0f + 2.0f * gamma<float>(3));
    __m128 t0 = _mm_set1_ps(-kInf), t1 = _mm_set1_ps(kInf);
    for (int axis = 0; axis < 3; ++axis) {
      const __m128 near = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[nearRow_[axis]]), o_[axis]), inv_[axis]);
      const __m128 far = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[farRow_[axis]]), o_[axis]), inv_[axis]);
      t0 = _mm_max_ps(near, t0);
      t1 = _mm_min_ps(_mm_mul_ps(far, widen), t1);
    }
    const __m128 inside = _mm_and_ps(_mm_cmple_ps(t0, t1), _mm_cmpgt_ps(t1, _mm_setzero_ps()));
    const __m128 hit = _mm_and_ps(inside, _mm_cmplt_ps(t0, _mm_set1_ps(tMax)));
    _mm_storeu_ps(tEntry, t0);
    return _mm_movemask_ps(hit);
  }

 private:
  __m128 o_[3], inv_[3];
  int nearRow_[3], farRow_[3];
  Ray<float> ray_;
  Vec3<float> invDir_;
  int dirIsNeg_[3];
};
}  // namespace

// All four children's boxes are tested at once. Embree's order of cases: no child
// hit pops the stack; one is entered without touching the stack; of two, the farther
// is pushed; three or four are pushed sorted, nearest on top, and the nearest popped.
// Ties go to the lower child slot, so a given tree always meets hits in one order.
// A popped entry is skipped when the nearest hit found meanwhile is closer than where
// the ray enters its box. The per-ray parts of the box and triangle tests are computed once.
template <typename T, bool kAnyHit>
std::optional<BvhHit<T>> Bvh::traverse(const Ray<T>& rayIn) const {
  if (triangles_.empty()) return std::nullopt;
  Ray<T> ray = rayIn;
  const ChildBoxTest<T> boxTest(ray);
  T tRoot = 0;
  if (!boxTest.root(rootBounds_, tRoot)) return std::nullopt;
  const TriangleRay<T> triRay(ray);
  std::optional<BvhHit<T>> best;
  struct Entry {
    std::uint32_t ref;
    T tEntry;
  };
  Entry stack[kStackSize];
  int top = 0;
  std::uint32_t ref = root_;
  for (;;) {
    while (!isLeaf(ref)) {
      const Node4& node = nodes_[ref];
      // The children's references lie in the node's second cache line: ask for it now,
      // so that its miss overlaps the box test on the first.
      _mm_prefetch(reinterpret_cast<const char*>(&node) + 64, _MM_HINT_T0);
      T tEntry[4];
      unsigned mask = unsigned(boxTest(node, ray.tMax, tEntry));
      if (mask == 0) goto pop;
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {
        ref = node.child[i];
        continue;
      }
      const int j = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {
        const bool iFirst = tEntry[i] <= tEntry[j];
        stack[top++] = iFirst ? Entry{node.child[j], tEntry[j]} : Entry{node.child[i], tEntry[i]};
        ref = iFirst ? node.child[i] : node.child[j];
        continue;
      }
      // Each later child has a higher slot, so on a tie it goes below the ones there.
      const int base = top;
      const auto push = [&](int k) {
        const Entry e{node.child[k], tEntry[k]};
        int at = top++;
        for (; at > base && stack[at - 1].tEntry <= e.tEntry; --at) stack[at] = stack[at - 1];
        stack[at] = e;
      };
      push(i);
      push(j);
      for (; mask != 0; mask &= mask - 1) push(__builtin_ctz(mask));
      ref = stack[--top].ref;
    }
    {
      const std::uint32_t first = leafFirst(ref), end = first + leafCount(ref);
      for (std::uint32_t k = first; k < end; ++k) {
        const TriangleVerts& tri = triangles_[k];
        if (auto hit = intersectTriangle(triRay, ray.tMax, toT<T>(tri.p0), toT<T>(tri.p1), toT<T>(tri.p2))) {
          best = BvhHit<T>{*hit, order_[k]};
          if constexpr (kAnyHit) return best;
          ray.tMax = hit->t;
        }
      }
    }
  pop:
    // The next box the ray still enters before its nearest hit.
    do {
      if (top == 0) return best;
      --top;
    } while (!(stack[top].tEntry < ray.tMax));
    ref = stack[top].ref;
  }
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
