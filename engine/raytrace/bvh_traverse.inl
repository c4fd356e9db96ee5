// The BVH traversal, written once and compiled once per instruction set:
// bvh_traverse.cpp includes this file inside namespace sse, again inside namespace
// avx2 under ENGINE_AVX2_BEGIN, and once more inside namespace avx512 under
// ENGINE_AVX512_BEGIN (Embree's way: the same source, one copy per ISA, the best
// picked at run time). No include guard, no includes: the including namespace
// provides BoxTest<T> (the children's boxes against a ray), LeafTest<T> and toT.
//
// All of a node's children's boxes are tested at once. Embree's order of cases: no
// child hit pops the stack; one is entered without touching the stack; of two, the
// farther is pushed; more are pushed sorted, nearest on top, and the nearest popped
// (for any hit: the first entered, the others pushed unsorted).
// Ties go to the lower child slot, so a given tree always meets hits in one order. A
// popped entry is skipped when the nearest hit found meanwhile is closer than where
// the ray enters its box. The per-ray parts of the box and triangle tests are
// computed once. Returns whether anything was hit; the nearest hit (kAnyHit: the
// first found) goes to `best`. A bool and an out-parameter rather than an optional:
// building the optional's return value cost a store-forwarding stall per ray.
template <typename T, bool kAnyHit>
bool traverse(const Bvh::View& bvh, const Ray<T>& rayIn, BvhHit<T>& best) {
  // No test of the root's own box: its children's boxes are tested first thing
  // (Embree does the same), and a root that is a leaf is tested exactly anyway.
  Ray<T> ray = rayIn;
  const BoxTest<T> boxTest(ray);
  const LeafTest<T> leafTest(ray);
  bool found = false;
  struct Entry {
    std::uint32_t ref;
    T tEntry;
  };
  Entry stack[Bvh::kStackSize];
  int top = 0;
  std::uint32_t ref = bvh.root;
  for (;;) {
    while (!Bvh::isLeaf(ref)) {
      const Bvh::Node& node = bvh.nodes[ref];
      // A node is four cache lines; ask for the three after the one the test starts on.
      for (int line = 1; line < int(sizeof(Bvh::Node) / 64); ++line) {
        _mm_prefetch(reinterpret_cast<const char*>(&node) + 64 * line, _MM_HINT_T0);
      }
      T tEntry[Bvh::kWidth];
      unsigned mask = unsigned(boxTest(node, ray.tMax, tEntry));
      if (mask == 0) goto pop;
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      if (mask == 0) {
        ref = node.child[i];
        continue;
      }
      if constexpr (kAnyHit) {
        // Any hit ends the search, so the order matters little: Embree does not sort
        // for occlusion either. The first child is entered, the others pushed.
        for (; mask != 0; mask &= mask - 1) {
          const int k = __builtin_ctz(mask);
          stack[top++] = Entry{node.child[k], tEntry[k]};
        }
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
      const std::uint32_t leaf = Bvh::leafIndex(ref);
      TriangleIntersection<T> hit{};
      const int lane = leafTest.template intersect<kAnyHit>(bvh.leaves[leaf], Bvh::leafCount(ref), ray.tMax, hit);
      if (lane >= 0) {
        best = BvhHit<T>{hit, bvh.order[4 * leaf + std::uint32_t(lane)]};
        found = true;
        if constexpr (kAnyHit) return true;
      }
    }
  pop:
    // The next box the ray still enters before its nearest hit.
    do {
      if (top == 0) return found;
      --top;
    } while (!(stack[top].tEntry < ray.tMax));
    ref = stack[top].ref;
  }
}
