// Eight rays through the BVH together (Bvh::intersect8), for coherent rays such as a
// camera's 4 x 2 pixels. Each node's eight boxes are tested once for the whole
// packet, against the interval its origins and inverse directions span; each leaf's
// triangles are tested against all eight rays at once, lane by lane the operations of
// intersectTriangle, so that every ray's nearest distance is the single-ray
// traversal's bit for bit.
//
// Why the interval test loses no hit: rounding is monotonic, so for a ray whose
// origin lies in [oLo, oHi] and inverse direction in [invLo, invHi] (one sign), its
// rounded (slab - o) * inv lies between the smallest and the largest of the four
// corners' rounded products. The packet's entry distance (the largest over the axes of
// the smallest corner) is then at most each ray's, its exit distance (the smallest
// over the axes of the largest corner, widened as the single-ray test widens) at least
// each ray's; a box that any of the rays enters passes. A ray may meet more leaves
// than alone, never fewer, and the nearest of more candidates is the same nearest.
// Packets whose rays differ in the sign of a direction component or in the axis the
// watertight test shears along, or have a zero component, are traced one ray at a time.
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "raytrace/avx2_region.h"
#include "raytrace/bvh.h"

namespace engine::rt {

ENGINE_AVX2_BEGIN
namespace avx2 {
#include "raytrace/bvh_packet.inl"
}  // namespace avx2
ENGINE_AVX2_END

ENGINE_AVX512_BEGIN
namespace avx512 {
#include "raytrace/bvh_packet.inl"
}  // namespace avx512
ENGINE_AVX512_END

bool Bvh::tracePacket8(const Ray<float>* rays, BvhHit<float>* hits, std::uint32_t& hitMask) const {
  if (triangleCount_ == 0) return false;
  if (isa() == Isa::kAvx512) return avx512::tracePacketAvx2(view(), rays, hits, hitMask);
  return cpuHasAvx2() && avx2::tracePacketAvx2(view(), rays, hits, hitMask);
}

std::uint32_t Bvh::intersect8(std::span<const Ray<float>, kPacketSize> rays,
                              std::span<BvhHit<float>, kPacketSize> hits) const {
  if (triangleCount_ == 0) return 0;
  std::uint32_t mask = 0;
  if (isa() != Isa::kSse2 && tracePacket8(rays.data(), hits.data(), mask)) return mask;
  for (int lane = 0; lane < kPacketSize; ++lane) {
    if (const auto hit = intersect(rays[std::size_t(lane)])) {
      hits[std::size_t(lane)] = *hit;
      mask |= 1u << lane;
    }
  }
  return mask;
}

}  // namespace engine::rt
