#include "anim/key_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace engine {
namespace {

// A group's floats in one interval: `lanes` floats per component array.
struct Lanes {
  const float* data;
  std::size_t lanes;
  const float* operator[](std::size_t array) const { return data + array * lanes; }
};

#if defined(__SSE2__)
// glm::dot of two quaternions, lane by lane: (w w' + x x') + (y y' + z z').
__m128 dot4(__m128 ax, __m128 ay, __m128 az, __m128 aw, __m128 bx, __m128 by, __m128 bz, __m128 bw) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(aw, bw), _mm_mul_ps(ax, bx)),
                    _mm_add_ps(_mm_mul_ps(ay, by), _mm_mul_ps(az, bz)));
}

// slerpSin, lane by lane.
__m128 sin4(__m128 x) {
  const __m128 x2 = _mm_mul_ps(x, x);
  __m128 p = _mm_set1_ps(kSinPolynomial[0]);
  for (int i = 1; i < 5; ++i) p = _mm_add_ps(_mm_mul_ps(p, x2), _mm_set1_ps(kSinPolynomial[i]));
  return _mm_add_ps(x, _mm_mul_ps(_mm_mul_ps(x, x2), p));
}

// Slerp's weights for four rotations, or nlerp's: slerpAt's expressions exactly,
// lane by lane. theta is 0 where the arc hands over to nlerp (slerpArc's `nlerp`),
// and above 0 otherwise (twice the atan2 of a |a - b| of at least kSlerpNlerpBelow).
void rotationWeights4(const float* theta, const float* invSin, float u, QuatInterpolation method, __m128& wa,
                      __m128& wb) {
  wa = _mm_set1_ps(1.0f - u), wb = _mm_set1_ps(u);
  if (method != QuatInterpolation::Slerp) return;
  const __m128 th = _mm_loadu_ps(theta), slerps = _mm_cmpgt_ps(th, _mm_setzero_ps());
  if (_mm_movemask_ps(slerps) == 0) return;
  const __m128 inv = _mm_loadu_ps(invSin);
  const __m128 sa = _mm_mul_ps(sin4(_mm_mul_ps(wa, th)), inv), sb = _mm_mul_ps(sin4(_mm_mul_ps(wb, th)), inv);
  wa = _mm_or_ps(_mm_and_ps(slerps, sa), _mm_andnot_ps(slerps, wa));
  wb = _mm_or_ps(_mm_and_ps(slerps, sb), _mm_andnot_ps(slerps, wb));
}

// a + d u for four tracks at once, then each into its joint.
void lerpLanes(Lanes f, std::span<const std::uint32_t> joints, float u, std::span<Srt> out, glm::vec3 Srt::*part) {
  const __m128 uu = _mm_set1_ps(u);
  for (std::size_t g = 0; g < joints.size(); g += 4) {
    alignas(16) float r[3][4];
    for (std::size_t c = 0; c < 3; ++c)
      _mm_store_ps(r[c], _mm_add_ps(_mm_loadu_ps(f[c] + g), _mm_mul_ps(_mm_loadu_ps(f[3 + c] + g), uu)));
    const std::size_t n = std::min<std::size_t>(4, joints.size() - g);
    for (std::size_t l = 0; l < n; ++l) out[joints[g + l]].*part = glm::vec3(r[0][l], r[1][l], r[2][l]);
  }
}

// safeNormalize(a wa + b wb) for four rotations at once (b is in a's hemisphere
// already): the square root and division that are most of slerp's and nlerp's cost,
// four for the price of one.
void rotateLanes(Lanes f, std::span<const std::uint32_t> joints, float u, QuatInterpolation method,
                 std::span<Srt> out) {
  for (std::size_t g = 0; g < joints.size(); g += 4) {
    const __m128 ax = _mm_loadu_ps(f[0] + g), ay = _mm_loadu_ps(f[1] + g), az = _mm_loadu_ps(f[2] + g),
                 aw = _mm_loadu_ps(f[3] + g);
    const __m128 bx = _mm_loadu_ps(f[4] + g), by = _mm_loadu_ps(f[5] + g), bz = _mm_loadu_ps(f[6] + g),
                 bw = _mm_loadu_ps(f[7] + g);
    __m128 wa, wb;
    rotationWeights4(f[8] + g, f[9] + g, u, method, wa, wb);
    const __m128 qx = _mm_add_ps(_mm_mul_ps(ax, wa), _mm_mul_ps(bx, wb));
    const __m128 qy = _mm_add_ps(_mm_mul_ps(ay, wa), _mm_mul_ps(by, wb));
    const __m128 qz = _mm_add_ps(_mm_mul_ps(az, wa), _mm_mul_ps(bz, wb));
    const __m128 qw = _mm_add_ps(_mm_mul_ps(aw, wa), _mm_mul_ps(bw, wb));
    // safeNormalize: hasDirection is len2 >= FLT_MIN and finite (both compares are
    // false for NaN); identity where it fails (the padding lanes, all zero, too).
    const __m128 len2 = dot4(qx, qy, qz, qw, qx, qy, qz, qw);
    const __m128 ok = _mm_and_ps(_mm_cmpge_ps(len2, _mm_set1_ps(std::numeric_limits<float>::min())),
                                 _mm_cmplt_ps(len2, _mm_set1_ps(std::numeric_limits<float>::infinity())));
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(len2));
    __m128 rx = _mm_and_ps(ok, _mm_mul_ps(qx, inv)), ry = _mm_and_ps(ok, _mm_mul_ps(qy, inv));
    __m128 rz = _mm_and_ps(ok, _mm_mul_ps(qz, inv));
    __m128 rw = _mm_or_ps(_mm_and_ps(ok, _mm_mul_ps(qw, inv)), _mm_andnot_ps(ok, _mm_set1_ps(1.0f)));
    _MM_TRANSPOSE4_PS(rx, ry, rz, rw);  // one quaternion (x, y, z, w as glm keeps them) per register
    const __m128 rows[4] = {rx, ry, rz, rw};
    static_assert(sizeof(glm::quat) == 16 && offsetof(glm::quat, x) == 0 && offsetof(glm::quat, w) == 12);
    const std::size_t n = std::min<std::size_t>(4, joints.size() - g);
    for (std::size_t l = 0; l < n; ++l) _mm_storeu_ps(&out[joints[g + l]].rotation.x, rows[l]);
  }
}
#else
// rotationWeights4's, for one rotation.
void rotationWeights(float theta, float invSin, float u, QuatInterpolation method, float& wa, float& wb) {
  if (method == QuatInterpolation::Slerp && theta > 0.0f) {
    wa = slerpSin((1.0f - u) * theta) * invSin;
    wb = slerpSin(u * theta) * invSin;
  } else {
    wa = 1.0f - u;
    wb = u;
  }
}

void lerpLanes(Lanes f, std::span<const std::uint32_t> joints, float u, std::span<Srt> out, glm::vec3 Srt::*part) {
  for (std::size_t l = 0; l < joints.size(); ++l)
    out[joints[l]].*part = glm::vec3(f[0][l], f[1][l], f[2][l]) + glm::vec3(f[3][l], f[4][l], f[5][l]) * u;
}

void rotateLanes(Lanes f, std::span<const std::uint32_t> joints, float u, QuatInterpolation method,
                 std::span<Srt> out) {
  for (std::size_t l = 0; l < joints.size(); ++l) {
    float wa = 0.0f, wb = 0.0f;
    rotationWeights(f[8][l], f[9][l], u, method, wa, wb);
    const glm::quat a(f[3][l], f[0][l], f[1][l], f[2][l]), b(f[7][l], f[4][l], f[5][l], f[6][l]);
    out[joints[l]].rotation = safeNormalize(a * wa + b * wb);
  }
}
#endif

}  // namespace

KeyBlocks::KeyBlocks(std::span<const Track> tracks, std::span<const std::uint32_t> linear, std::size_t keys)
    : tracks_(linear.begin(), linear.end()) {
  std::vector<std::uint32_t> byPath[3];
  for (std::uint32_t i : linear) byPath[static_cast<int>(tracks[i].path)].push_back(i);
  auto place = [&](Group& group, const std::vector<std::uint32_t>& ids, std::size_t arrays) {
    for (std::uint32_t i : ids) group.joints.push_back(static_cast<std::uint32_t>(tracks[i].joint));
    group.lanes = (ids.size() + 3) / 4 * 4;
    group.offset = stride_;
    stride_ += group.lanes * arrays;
  };
  place(translations_, byPath[static_cast<int>(AnimPath::Translation)], 6);
  place(scales_, byPath[static_cast<int>(AnimPath::Scale)], 6);
  place(rotations_, byPath[static_cast<int>(AnimPath::Rotation)], 10);
  const std::size_t intervals = keys > 1 ? keys - 1 : 0;
  data_.assign(intervals * stride_, 0.0f);  // padding lanes: zero, so identity rotations
  for (std::size_t k = 0; k < intervals; ++k) {
    fillVec3(tracks, byPath[static_cast<int>(AnimPath::Translation)], translations_, k);
    fillVec3(tracks, byPath[static_cast<int>(AnimPath::Scale)], scales_, k);
    fillRotations(tracks, byPath[static_cast<int>(AnimPath::Rotation)], k);
  }
}

// Arrays a.x, a.y, a.z, d.x, d.y, d.z, where d = b - a: a + (b - a) u, as the track's
// own lerp computes it.
void KeyBlocks::fillVec3(std::span<const Track> tracks, std::span<const std::uint32_t> ids, const Group& group,
                         std::size_t interval) {
  float* f = data_.data() + interval * stride_ + group.offset;
  for (std::size_t l = 0; l < ids.size(); ++l) {
    const std::vector<glm::vec4>& v = tracks[ids[l]].values;
    const glm::vec3 a(v[interval]), d = glm::vec3(v[interval + 1]) - a;
    for (int c = 0; c < 3; ++c) {
      f[std::size_t(c) * group.lanes + l] = a[c];
      f[std::size_t(3 + c) * group.lanes + l] = d[c];
    }
  }
}

// Arrays a.x-w, b.x-w, theta, 1 / sin theta: b is the second key in the first's
// hemisphere (nlerp's flip and slerpArc's are the same test), theta and its
// inverse sine slerpArc's (0 where it hands over to nlerp).
void KeyBlocks::fillRotations(std::span<const Track> tracks, std::span<const std::uint32_t> ids,
                              std::size_t interval) {
  const std::size_t lanes = rotations_.lanes;
  float* f = data_.data() + interval * stride_ + rotations_.offset;
  for (std::size_t l = 0; l < ids.size(); ++l) {
    const std::vector<glm::vec4>& v = tracks[ids[l]].values;
    const glm::quat a = toQuat(v[interval]);
    const SlerpArc arc = slerpArc(a, toQuat(v[interval + 1]));
    const float values[10] = {a.x, a.y, a.z, a.w, arc.b.x, arc.b.y, arc.b.z, arc.b.w, arc.theta, arc.invSin};
    for (std::size_t c = 0; c < 10; ++c) f[c * lanes + l] = values[c];
  }
}

void KeyBlocks::sample(const KeyPair& k, QuatInterpolation method, std::span<Srt> output) const {
  const float* interval = data_.data() + k.first * stride_;
  lerpLanes({interval + translations_.offset, translations_.lanes}, translations_.joints, k.u, output,
            &Srt::translation);
  lerpLanes({interval + scales_.offset, scales_.lanes}, scales_.joints, k.u, output, &Srt::scale);
  rotateLanes({interval + rotations_.offset, rotations_.lanes}, rotations_.joints, k.u, method, output);
}

}  // namespace engine
