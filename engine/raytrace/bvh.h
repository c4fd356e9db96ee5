#pragma once
// A bounding volume hierarchy over triangles, shaped after Embree's BVH8 with
// Triangle4 leaves: built top-down as a binary tree with the binned surface area
// heuristic (all three axes, leaves costed in blocks of four triangles, triangles in
// an axis-aligned plane split from the rest of a leaf: see bvh.cpp), then
// collapsed into an 8-wide tree whose node holds its eight children's boxes side by
// side, so that one ray tests them all at once: with AVX2 where the CPU has it
// (chosen at run time), otherwise as two halves with SSE. A leaf holds up to four
// triangles as structure of arrays, tested together with the watertight test.
// Stored flat in depth-first order (children follow their parent), refitted bottom-up
// when vertices move but the triangles stay the same, rebuilt when they do not. The
// build runs on TBB's threads and gives the same tree on any number of them.
#include <cstddef>
#include <cstdint>
#include <memory>
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
  // Triangles of any size, degenerate ones included (they are never hit); fewer
  // than 2^28 of them (std::length_error otherwise). Nodes of at least `grain`
  // triangles build their two sides at once, and passes over at least four times as
  // many run in parts of `grain`, on TBB's threads; the tree is the same bits for any
  // grain and any number of threads (kSerial: all on the calling thread).
  static constexpr std::size_t kParallelGrain = 2048;
  static constexpr std::size_t kSerial = SIZE_MAX;
  void build(std::span<const TriangleVerts> triangles, std::size_t grain = kParallelGrain);
  // The same triangles as the last build(), in the same order, at new positions.
  // The tree keeps its shape, so traversal slows as the motion grows; rebuild then.
  void refit(std::span<const TriangleVerts> triangles);

  // The nearest hit in (0, ray.tMax).
  template <typename T>
  std::optional<BvhHit<T>> intersect(const Ray<T>& ray) const;
  // Any hit in (0, ray.tMax): shadow rays stop at the first one.
  template <typename T>
  bool intersectAny(const Ray<T>& ray) const;

  // Eight rays at once, each answered as intersect() answers it: the same nearest
  // distance bit for bit (of triangles at an equal distance, either may be named).
  // For coherent rays, such as a camera's 4 x 2 pixels (bvh_packet.cpp): the eight go
  // through the tree together. Rays that differ in a direction component's sign or in
  // their largest axis, or have a zero component, and every packet without AVX2, are
  // traced one at a time. Returns the mask of the rays that hit; hits[i] is set for those.
  static constexpr int kPacketSize = 8;
  std::uint32_t intersect8(std::span<const Ray<float>, kPacketSize> rays,
                           std::span<BvhHit<float>, kPacketSize> hits) const;
  // intersect8's packet traversal alone (AVX2 only; tests call it to know it ran):
  // false, and nothing traced, when the eight rays cannot share a traversal.
  bool tracePacket8(const Ray<float>* rays, BvhHit<float>* hits, std::uint32_t& hitMask) const;

  bool empty() const { return triangleCount_ == 0; }
  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t triangleCount() const { return triangleCount_; }
  int depth() const { return depth_; }
  Bounds3f bounds() const { return rootBounds_; }

  // A leaf's triangles as structure of arrays, p[vertex][axis][lane], so that one ray
  // tests all four at once (Embree's Triangle4). Lanes past the leaf's count are
  // zero and never tested.
  struct alignas(16) Triangle4 {
    float p[3][3][4];
    glm::vec3 vertex(int v, int lane) const { return {p[v][0][lane], p[v][1][lane], p[v][2][lane]}; }
  };

  // A child reference in one word: an interior node's index, or (top bit set) a leaf
  // of 1-4 triangles, its count - 1 in bits 28-29 and its Triangle4 below; an unused
  // slot is kNoChild. Traversal entries are then a word and a distance.
  static constexpr std::uint32_t kLeafBit = 0x80000000u;
  static constexpr std::uint32_t kNoChild = 0xffffffffu;
  static constexpr std::uint32_t kMaxTriangles = 1u << 28;
  static constexpr bool isLeaf(std::uint32_t ref) { return (ref & kLeafBit) != 0; }
  static constexpr std::uint32_t leafIndex(std::uint32_t ref) { return ref & (kMaxTriangles - 1); }
  static constexpr std::uint32_t leafCount(std::uint32_t ref) { return ((ref >> 28) & 3u) + 1; }
  static constexpr std::uint32_t leafRef(std::uint32_t block, std::uint32_t count) {
    return kLeafBit | ((count - 1) << 28) | block;
  }

  // Eight children's boxes as structure of arrays: box[0..2] the min x, y, z and
  // box[3..5] the max x, y, z of children 0-7, one AVX register each. An unused slot
  // has an empty box (min +inf, max -inf), which every ray misses.
  static constexpr int kWidth = 8;
  struct alignas(64) Node {
    float box[6][kWidth];
    std::uint32_t child[kWidth];  // references, as above
  };
  static_assert(sizeof(Node) == 256, "a node in four aligned cache lines");

  // Past kMaxSahDepth the builder splits at the object median, so whatever the
  // triangles look like the binary tree is at most kMaxSahDepth + 28 levels deep
  // (fewer than 2^28 triangles); each level of the collapsed tree pushes at most
  // kWidth - 1 entries, so the traversal stack cannot overflow.
  static constexpr int kMaxSahDepth = 48;
  static constexpr int kStackSize = (kWidth - 1) * (kMaxSahDepth + 28) + 1;

  // One node's eight boxes against a float ray, as the traversal tests a node's
  // children (the same answers bit for bit): the mask of the boxes entered before tMax
  // and their entry distances. For a caller's own node of boxes (RtScene's roots).
  static int testBoxes(const Node& node, const Ray<float>& ray, float tMax, float tEntry[kWidth]);
  // What the traversal reads; also what gputrace/gpu_layout.h flattens for the GPU.
  struct View {
    const Node* nodes;
    const Triangle4* leaves;
    const std::uint32_t* order;
    std::uint32_t root;
  };
  View view() const { return View{nodes_.data(), leaves_.data(), order_.data(), root_}; }
  std::size_t leafCount() const { return leaves_.size(); }  // Triangle4 blocks

  // The instruction set of float traversal: the best the CPU has unless set otherwise
  // (tests and benchmarks run each). kAvx512 is the AVX2 code compiled with AVX-512VL
  // allowed (more registers, the same bits). setIsa to one the CPU lacks is ignored.
  enum class Isa { kSse2, kAvx2, kAvx512 };
  static Isa isa();
  static void setIsa(Isa isa);
  static const char* isaName(Isa isa);  // "SSE2", "AVX2", "AVX2 with AVX-512VL"

 private:
  // Both queries: the traversal for this CPU and precision.
  template <typename T, bool kAnyHit>
  bool trace(const Ray<T>& ray, BvhHit<T>& hit) const;

  // The binary tree the builder makes; collapsed into Nodes, then dropped.
  struct BinaryNode {
    Bounds3f bounds;
    std::uint32_t offset = 0;  // leaf: its Triangle4; interior: second child
    std::uint16_t count = 0;   // triangles in a leaf, 0 for an interior node
  };

  struct BuildPrim {
    Bounds3f bounds;
    glm::vec3 centroid;
    std::uint32_t index;
  };

  // A part of the binary tree built on its own, numbered from 0: its nodes, its leaf
  // slots (as order_) and the depth reached.
  struct Subtree {
    std::vector<BinaryNode> nodes;
    std::vector<std::uint32_t> order;
    int depth = 0;
  };
  struct Cut {
    Bounds3f bounds;
    std::size_t mid = 0;
    bool leaf = false;
  };
  struct Piece;

  static Cut cut(std::span<BuildPrim> prims, int depth, std::size_t grain);
  static std::uint32_t buildRecursive(std::span<BuildPrim> prims, int depth, Subtree& out);
  static std::uint32_t makeLeaf(std::span<BuildPrim> prims, Subtree& out);
  static std::unique_ptr<Piece> buildTop(std::span<BuildPrim> prims, int depth, std::size_t grain);
  void append(Piece& piece);
  void fillLeaves(std::span<const TriangleVerts> triangles, std::size_t grain);
  std::uint32_t collapse(std::uint32_t binary);
  std::uint32_t reference(std::uint32_t binary);
  Bounds3f childBounds(std::uint32_t ref) const;
  void refitNode(std::uint32_t index);

  std::vector<BinaryNode> binary_;           // during build() only
  std::vector<Node> nodes_;
  Bounds3f rootBounds_;
  std::uint32_t root_ = kNoChild;            // a reference, like a Node's child
  std::vector<std::uint32_t> order_;         // 4 * leaf + lane -> index given to build(), kNoChild
  std::vector<Triangle4> leaves_;            // in the order the tree's leaves were made
  std::size_t triangleCount_ = 0;
  int depth_ = 0;
};

}  // namespace engine::rt
