#include "raytrace/bvh.h"

#include <emmintrin.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

namespace engine::rt {
namespace {

constexpr int kBins = 32;
constexpr std::uint32_t kMaxLeafTriangles = 4;  // a leaf reference holds 1-4
// SAH costs relative to one test of four triangles at once.
constexpr float kTraversalCost = 1.0f;  // Embree's

Bounds3f triangleBounds(const TriangleVerts& t) {
  Bounds3f b;
  b.extend(t.p0);
  b.extend(t.p1);
  b.extend(t.p2);
  return b;
}

struct Split {
  int axis = -1;
  int bins = kBins;  // of the binning it was found in
  int bin = 0;       // primitives in bins [0, bin] go left
  float cost = 0.0f;
};

// Triangles are tested four at a time, so the SAH counts blocks of four.
float leafCost(std::uint32_t triangles) { return float((triangles + 3) / 4); }

// A would-be leaf's triangles that lie in one axis-aligned plane, moved to the front
// when the others do not all lie in it: how many, or 0. The caller then splits them
// off, so that a floor or a wall gets leaves with flat boxes of their own. The SAH
// alone kept them in a leaf with triangles of what stands on them (a block of four
// costs the same however full), and that leaf's box has height: every shadow ray or
// bounce leaving the floor starts inside it and tests all four triangles. The SAH
// cannot see it, taking rays to come from outside a box rather than to start on a
// surface within it; a flat box is missed by every ray that leaves its plane.
template <typename Prim>
std::size_t flatGroupFirst(std::span<Prim> prims, const Bounds3f& bounds) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!(bounds.max[axis] > bounds.min[axis])) continue;  // all in one plane already
    for (const Prim& p : prims) {
      if (p.bounds.min[axis] != p.bounds.max[axis]) continue;
      const float plane = p.bounds.min[axis];
      const auto inPlane = [&](const Prim& q) { return q.bounds.min[axis] == plane && q.bounds.max[axis] == plane; };
      return std::size_t(std::partition(prims.begin(), prims.end(), inPlane) - prims.begin());
    }
  }
  return 0;
}

// A pass over a node's primitives, in parts of `grain` across threads where there are
// at least four parts: `of` sums up a part and `join` adds two sums. Counts and boxes
// sum to the same bits in any order (integer sums, minima and maxima of finite
// coordinates), so the result is the one-part result.
template <typename Sum, typename Prim, typename Of, typename Join>
Sum reduceOver(std::span<const Prim> prims, std::size_t grain, const Of& of, const Join& join) {
  if (prims.size() / 4 < grain) return of(prims);
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, prims.size(), grain), Sum{},
      [&](const tbb::blocked_range<std::size_t>& r, Sum sum) {
        return join(std::move(sum), of(prims.subspan(r.begin(), r.size())));
      },
      join);
}

// f(begin, end) over [0, n) in parts of `grain` across threads, or at once where there
// are fewer than four parts.
template <typename F>
void forParts(std::size_t n, std::size_t grain, const F& f) {
  if (n / 4 < grain) return f(0, n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
}

int binIndex(float c, float lo, float extent, int bins) {
  const int b = int(float(bins) * ((c - lo) / extent));
  return std::clamp(b, 0, bins - 1);
}

// A box as two SSE registers (lane 3 unused), extended as Bounds3f::extend extends:
// glm::min(a, b) is (b < a) ? b : a, which is _mm_min_ps(b, a) in every case (signed
// zeros and NaN included), and glm::max(a, b), (a < b) ? b : a, is _mm_max_ps(b, a).
struct SimdBox {
  __m128 min, max;

  static SimdBox empty() {
    return {_mm_set1_ps(std::numeric_limits<float>::infinity()), _mm_set1_ps(-std::numeric_limits<float>::infinity())};
  }
  void extend(__m128 lo, __m128 hi) {
    min = _mm_min_ps(lo, min);
    max = _mm_max_ps(hi, max);
  }
  void extend(const SimdBox& b) { extend(b.min, b.max); }
  Bounds3f bounds() const {
    alignas(16) float lo[4], hi[4];
    _mm_store_ps(lo, min);
    _mm_store_ps(hi, max);
    return Bounds3f{glm::vec3(lo[0], lo[1], lo[2]), glm::vec3(hi[0], hi[1], hi[2])};
  }
};

// A primitive's box and centroid as registers. Each load reads 16 bytes from a field of
// 12, the next field's first float in lane 3, which no result reads. The centroid's is
// the index, whose bits as a float are denormal, and arithmetic on a denormal costs
// the CPU a hundred cycles: that lane is cleared.
template <typename Prim>
__m128 primMin(const Prim& p) {
  static_assert(offsetof(Prim, bounds) == 0 && offsetof(Prim, centroid) == 24 && sizeof(Prim) == 40);
  return _mm_loadu_ps(&p.bounds.min.x);
}
template <typename Prim>
__m128 primMax(const Prim& p) {
  return _mm_loadu_ps(&p.bounds.max.x);
}
template <typename Prim>
__m128 primCentroid(const Prim& p) {
  return _mm_and_ps(_mm_loadu_ps(&p.centroid.x), _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)));
}

// The SAH's bins on each axis: the boxes and counts of the primitives binned there.
// Only the first `used` of each axis are set (a small node has few), and read; a sum
// of two (TBB's identity has all 32) reads the bins both have.
struct Bins {
  int used = kBins;
  std::array<std::array<SimdBox, kBins>, 3> box;
  std::array<std::array<std::uint32_t, kBins>, 3> count;

  Bins() : Bins(kBins) {}
  explicit Bins(int binCount) : used(binCount) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      std::fill_n(box[axis].begin(), binCount, SimdBox::empty());
      std::fill_n(count[axis].begin(), binCount, 0u);
    }
  }
  void add(const Bins& b) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      for (std::size_t i = 0; i < std::size_t(std::min(used, b.used)); ++i) {
        count[axis][i] += b.count[axis][i];
        box[axis][i].extend(b.box[axis][i]);
      }
    }
  }
};

// A centroid's bin on each axis, binIndex's arithmetic lane by lane (the same
// division, product, truncation and clamp, so the same bins as the partition's):
// lanes 0-2 of the result.
__m128i binIndices(__m128 c, __m128 lo, __m128 extent, __m128 bins, __m128i last) {
  __m128i b = _mm_cvttps_epi32(_mm_mul_ps(bins, _mm_div_ps(_mm_sub_ps(c, lo), extent)));
  b = _mm_and_si128(b, _mm_cmpgt_epi32(b, _mm_set1_epi32(-1)));  // below 0 (and the invalid INT_MIN): 0
  const __m128i over = _mm_cmpgt_epi32(b, last);
  return _mm_or_si128(_mm_and_si128(over, last), _mm_andnot_si128(over, b));
}

// The primitives binned by centroid on every axis in one pass, an axis to a lane: the
// bins and boxes of a scalar binning, bit for bit (binIndices, SimdBox), in two
// thirds of its time. An axis along which the centroids do not spread bins
// everything in bin 0.
template <typename Prim>
Bins binPrims(std::span<const Prim> prims, const Bounds3f& centroids, int binCount, std::size_t grain) {
  const glm::vec3 lo = centroids.min, extent = centroids.max - centroids.min;
  const bool spread[3] = {extent.x > 0.0f, extent.y > 0.0f, extent.z > 0.0f};
  // Other axes (and lane 3) divide by 1 (no zero divided by zero) and are masked to 0.
  const __m128 loV = _mm_setr_ps(lo.x, lo.y, lo.z, 0.0f);
  const __m128 extentV =
      _mm_setr_ps(spread[0] ? extent.x : 1.0f, spread[1] ? extent.y : 1.0f, spread[2] ? extent.z : 1.0f, 1.0f);
  const __m128i spreadMask = _mm_setr_epi32(spread[0] ? -1 : 0, spread[1] ? -1 : 0, spread[2] ? -1 : 0, 0);
  const __m128 binsV = _mm_set1_ps(float(binCount));
  const __m128i last = _mm_set1_epi32(binCount - 1);
  const auto binOf = [&](std::span<const Prim> part) {
    Bins bins(binCount);
    for (const Prim& p : part) {
      alignas(16) std::int32_t index[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(index),
                      _mm_and_si128(spreadMask, binIndices(primCentroid(p), loV, extentV, binsV, last)));
      const __m128 pMin = primMin(p), pMax = primMax(p);
      for (std::size_t axis = 0; axis < 3; ++axis) {
        bins.box[axis][std::size_t(index[axis])].extend(pMin, pMax);
        ++bins.count[axis][std::size_t(index[axis])];
      }
    }
    return bins;
  };
  return reduceOver<Bins>(prims, grain, binOf, [](Bins a, const Bins& b) {
    a.add(b);
    return a;
  });
}

// The cheapest binned SAH split over all three axes (Embree's binned builder; the
// widest axis alone left demo.json's primary rays a fifth slower). The primitives
// are binned (binPrims), then each axis is swept from the right for each suffix's
// area and count, then from the left. Costs are areas times leaf costs, not yet
// divided by the parent's area.
template <typename Prim>
Split bestSplit(std::span<const Prim> prims, const Bounds3f& centroids, std::size_t grain) {
  // Small nodes get fewer bins: 32 of them cost more to clear and sweep than binning
  // a handful of primitives, and made the builds of small meshes twice as slow.
  const int binCount = int(std::min<std::size_t>(kBins, std::max<std::size_t>(4, prims.size())));
  const Bins bins = binPrims(prims, centroids, binCount, grain);
  Split best;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (!(centroids.max[int(axis)] - centroids.min[int(axis)] > 0.0f)) continue;
    std::array<float, kBins> rightArea;
    std::array<std::uint32_t, kBins> rightCount;
    SimdBox acc = SimdBox::empty();
    std::uint32_t count = 0;
    for (int i = binCount - 1; i > 0; --i) {
      acc.extend(bins.box[axis][std::size_t(i)]);
      count += bins.count[axis][std::size_t(i)];
      rightArea[std::size_t(i)] = acc.bounds().surfaceArea();
      rightCount[std::size_t(i)] = count;
    }
    acc = SimdBox::empty();
    count = 0;
    for (int i = 0; i < binCount - 1; ++i) {
      acc.extend(bins.box[axis][std::size_t(i)]);
      count += bins.count[axis][std::size_t(i)];
      if (count == 0 || rightCount[std::size_t(i) + 1] == 0) continue;
      const float cost = acc.bounds().surfaceArea() * leafCost(count) +
                         rightArea[std::size_t(i) + 1] * leafCost(rightCount[std::size_t(i) + 1]);
      if (best.axis < 0 || cost < best.cost) best = Split{int(axis), binCount, i, cost};
    }
  }
  return best;
}

}  // namespace

std::uint32_t Bvh::makeLeaf(std::span<BuildPrim> prims, Subtree& out) {
  BinaryNode node;
  node.offset = std::uint32_t(out.order.size() / 4);
  node.count = std::uint16_t(prims.size());
  for (std::size_t lane = 0; lane < 4; ++lane) {
    if (lane < prims.size()) node.bounds.extend(prims[lane].bounds);
    out.order.push_back(lane < prims.size() ? prims[lane].index : kNoChild);
  }
  out.nodes.push_back(node);
  return std::uint32_t(out.nodes.size() - 1);
}

// Where a node's primitives divide: they are partitioned in place and the first `mid`
// go left; or, `leaf`, they make one leaf.
Bvh::Cut Bvh::cut(std::span<BuildPrim> prims, int depth, std::size_t grain) {
  Cut c;
  // The boxes of the primitives and of their centroids (SimdBox: Bounds3f::extend's bits).
  struct Boxes {
    SimdBox prims = SimdBox::empty(), centroids = SimdBox::empty();
  };
  const Boxes boxes = reduceOver<Boxes>(
      std::span<const BuildPrim>(prims), grain,
      [](std::span<const BuildPrim> part) {
        Boxes b;
        for (const BuildPrim& p : part) {
          b.prims.extend(primMin(p), primMax(p));
          const __m128 centroid = primCentroid(p);
          b.centroids.extend(centroid, centroid);
        }
        return b;
      },
      [](Boxes a, const Boxes& b) {
        a.prims.extend(b.prims);
        a.centroids.extend(b.centroids);
        return a;
      });
  c.bounds = boxes.prims.bounds();
  const Bounds3f centroids = boxes.centroids.bounds();
  const std::size_t n = prims.size();
  c.leaf = n <= 1;
  if (c.leaf) return c;

  const int widest = centroids.maxExtentAxis();
  bool split = false;
  // Within the SAH's depth only, as the SAH's own splits (the depth bound in bvh.h).
  const std::size_t flat = n <= kMaxLeafTriangles && depth < kMaxSahDepth ? flatGroupFirst(prims, c.bounds) : 0;
  if (flat > 0) {
    c.mid = flat;
    split = true;
  } else if (centroids.max[widest] > centroids.min[widest] && depth < kMaxSahDepth) {
    const Split best = bestSplit(std::span<const BuildPrim>(prims), centroids, grain);
    const float area = c.bounds.surfaceArea();
    const float splitCost = kTraversalCost + (area > 0.0f ? best.cost / area : 0.0f);
    const float asLeaf = leafCost(std::uint32_t(n));
    if (best.axis < 0 || (n <= kMaxLeafTriangles && asLeaf <= splitCost)) {
      c.leaf = n <= kMaxLeafTriangles;
      if (c.leaf) return c;
    } else {
      const float lo = centroids.min[best.axis], extent = centroids.max[best.axis] - lo;
      auto it = std::partition(prims.begin(), prims.end(), [&](const BuildPrim& p) {
        return binIndex(p.centroid[best.axis], lo, extent, best.bins) <= best.bin;
      });
      c.mid = std::size_t(it - prims.begin());
      split = c.mid > 0 && c.mid < n;
    }
  } else if (n <= kMaxLeafTriangles) {
    c.leaf = true;
    return c;
  }
  if (!split) {
    // Coincident centroids, too deep, or no useful SAH split: the object median.
    c.mid = n / 2;
    std::nth_element(prims.begin(), prims.begin() + std::ptrdiff_t(c.mid), prims.end(),
                     [&](const BuildPrim& a, const BuildPrim& b) { return a.centroid[widest] < b.centroid[widest]; });
  }
  return c;
}

std::uint32_t Bvh::buildRecursive(std::span<BuildPrim> prims, int depth, Subtree& out) {
  out.depth = std::max(out.depth, depth + 1);
  const Cut c = cut(prims, depth, kSerial);
  if (c.leaf) return makeLeaf(prims, out);
  const std::uint32_t index = std::uint32_t(out.nodes.size());
  out.nodes.push_back(BinaryNode{});
  buildRecursive(prims.subspan(0, c.mid), depth + 1, out);
  const std::uint32_t second = buildRecursive(prims.subspan(c.mid), depth + 1, out);
  out.nodes[index] = BinaryNode{c.bounds, second, 0};
  return index;
}

// The top of the tree, down to subtrees of fewer than `grain` triangles, with
// each node's two sides built at once (TBB); each subtree is built on its own as
// buildRecursive builds it, its nodes and leaf blocks numbered from 0. append() then
// lays them out depth first, as one buildRecursive over everything would have: the
// same tree, bit for bit, however many threads built it.
struct Bvh::Piece {
  Bounds3f bounds;
  int depth = 0;
  std::unique_ptr<Piece> left, right;  // a node of the top
  Subtree subtree;                     // or, with no sides, a subtree

  // Binary nodes and leaf slots, all told.
  std::pair<std::size_t, std::size_t> size() const {
    if (!left) return {subtree.nodes.size(), subtree.order.size()};
    const auto [ln, ls] = left->size();
    const auto [rn, rs] = right->size();
    return {1 + ln + rn, ls + rs};
  }
};

std::unique_ptr<Bvh::Piece> Bvh::buildTop(std::span<BuildPrim> prims, int depth, std::size_t grain) {
  auto piece = std::make_unique<Piece>();
  piece->depth = depth;
  Cut c;
  if (prims.size() >= grain) c = cut(prims, depth, grain);
  if (prims.size() < grain || c.leaf) {
    piece->subtree.nodes.reserve(2 * prims.size());
    piece->subtree.order.reserve(4 * prims.size());
    buildRecursive(prims, depth, piece->subtree);
    return piece;
  }
  piece->bounds = c.bounds;
  tbb::parallel_invoke([&] { piece->left = buildTop(prims.subspan(0, c.mid), depth + 1, grain); },
                       [&] { piece->right = buildTop(prims.subspan(c.mid), depth + 1, grain); });
  return piece;
}

void Bvh::append(Piece& piece) {
  if (!piece.left) {
    // A subtree's own numbers moved to where it lands: interior nodes name their
    // second child, leaves their first block.
    const auto nodeBase = std::uint32_t(binary_.size()), blockBase = std::uint32_t(order_.size() / 4);
    for (BinaryNode node : piece.subtree.nodes) {
      node.offset += node.count == 0 ? nodeBase : blockBase;
      binary_.push_back(node);
    }
    order_.insert(order_.end(), piece.subtree.order.begin(), piece.subtree.order.end());
    depth_ = std::max(depth_, piece.subtree.depth);  // buildRecursive counted its own root
    piece.subtree = {};
    return;
  }
  depth_ = std::max(depth_, piece.depth + 1);
  const std::uint32_t index = std::uint32_t(binary_.size());
  binary_.push_back(BinaryNode{});
  append(*piece.left);
  const std::uint32_t second = std::uint32_t(binary_.size());
  append(*piece.right);
  binary_[index] = BinaryNode{piece.bounds, second, 0};
}

// Gathers up to four descendants of a binary interior node, opening the largest
// interior one each time (its children are the likeliest to be visited), and makes
// them one Node; interior ones are collapsed in turn, after their parent.
std::uint32_t Bvh::collapse(std::uint32_t binary) {
  std::array<std::uint32_t, kWidth> kids{binary + 1, binary_[binary].offset};
  int n = 2;
  while (n < kWidth) {
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
  nodes_.push_back(Node{});
  for (int i = 0; i < kWidth; ++i) {
    const Bounds3f b = i < n ? binary_[kids[i]].bounds : Bounds3f{};
    const std::uint32_t child = i < n ? reference(kids[i]) : kNoChild;
    Node& node = nodes_[index];  // reference() may have moved the vector
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][i] = b.min[axis];
      node.box[3 + axis][i] = b.max[axis];
    }
    node.child[i] = child;
  }
  return index;
}

// A binary node as a Node's child: a leaf's triangles, or the interior node collapsed.
std::uint32_t Bvh::reference(std::uint32_t binary) {
  const BinaryNode& node = binary_[binary];
  return node.count > 0 ? leafRef(node.offset, node.count) : collapse(binary);
}

void Bvh::build(std::span<const TriangleVerts> triangles, std::size_t grain) {
  if (triangles.size() >= kMaxTriangles) throw std::length_error("Bvh::build: 2^28 triangles or more");
  nodes_.clear();
  binary_.clear();
  rootBounds_ = Bounds3f{};
  root_ = kNoChild;
  depth_ = 0;
  order_.clear();
  leaves_.clear();
  triangleCount_ = triangles.size();
  if (triangles.empty()) return;
  std::vector<BuildPrim> prims(triangles.size());
  forParts(prims.size(), grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) {
      prims[i].bounds = triangleBounds(triangles[i]);
      prims[i].centroid = prims[i].bounds.centroid();
      prims[i].index = std::uint32_t(i);
    }
  });
  const std::unique_ptr<Piece> top = buildTop(prims, 0, grain);
  const auto [nodes, slots] = top->size();
  binary_.reserve(nodes);
  order_.reserve(slots);
  append(*top);
  fillLeaves(triangles, grain);

  rootBounds_ = binary_[0].bounds;
  nodes_.reserve(binary_.size() / 12 + 1);  // about a seventh of the interior nodes
  root_ = reference(0);
  binary_ = {};  // the traversal reads only the Nodes
}

// A node's boxes from its children: leaves from their triangles, interior nodes from
// their own (already refitted) boxes.
Bounds3f Bvh::childBounds(std::uint32_t ref) const {
  Bounds3f b;
  if (isLeaf(ref)) {
    const Triangle4& leaf = leaves_[leafIndex(ref)];
    for (std::uint32_t lane = 0; lane < leafCount(ref); ++lane) {
      for (int v = 0; v < 3; ++v) b.extend(leaf.vertex(v, int(lane)));
    }
  } else {
    // Each slot as a box: an empty slot's (min +inf, max -inf) then changes nothing,
    // where its two corners taken as points would span all of space.
    const Node& kid = nodes_[ref];
    for (int j = 0; j < kWidth; ++j) {
      b.extend(Bounds3f{glm::vec3(kid.box[0][j], kid.box[1][j], kid.box[2][j]),
                        glm::vec3(kid.box[3][j], kid.box[4][j], kid.box[5][j])});
    }
  }
  return b;
}

void Bvh::refitNode(std::uint32_t index) {
  Node& node = nodes_[index];
  for (int i = 0; i < kWidth; ++i) {
    if (node.child[i] == kNoChild) continue;
    const Bounds3f b = childBounds(node.child[i]);
    for (int axis = 0; axis < 3; ++axis) {
      node.box[axis][i] = b.min[axis];
      node.box[3 + axis][i] = b.max[axis];
    }
  }
}

// The leaves' Triangle4s from the triangles in build() order; unused lanes zero.
void Bvh::fillLeaves(std::span<const TriangleVerts> triangles, std::size_t grain) {
  leaves_.assign(order_.size() / 4, Triangle4{});
  const auto fill = [&](std::size_t begin, std::size_t end) {
    for (std::size_t slot = begin; slot < end; ++slot) {
      if (order_[slot] == kNoChild) continue;
      const TriangleVerts& t = triangles[order_[slot]];
      Triangle4& leaf = leaves_[slot / 4];
      for (int axis = 0; axis < 3; ++axis) {
        leaf.p[0][axis][slot % 4] = t.p0[axis];
        leaf.p[1][axis][slot % 4] = t.p1[axis];
        leaf.p[2][axis][slot % 4] = t.p2[axis];
      }
    }
  };
  // Whole leaves to each part (a multiple of four slots), so no two write one leaf.
  forParts(leaves_.size(), grain, [&](std::size_t begin, std::size_t end) { fill(4 * begin, 4 * end); });
}

void Bvh::refit(std::span<const TriangleVerts> triangles) {
  if (triangleCount_ == 0) return;
  fillLeaves(triangles, kParallelGrain);
  // Children follow their parents, so a reverse sweep refits children first.
  for (std::size_t i = nodes_.size(); i-- > 0;) refitNode(std::uint32_t(i));
  rootBounds_ = childBounds(root_);
}

}  // namespace engine::rt
