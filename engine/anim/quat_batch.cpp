#include "anim/quat_batch.h"

#include <cstddef>
#include <limits>

#include "core/math.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace engine {

#if defined(__SSE2__)
namespace {

// glm::dot of two quaternions, lane by lane: (w w' + x x') + (y y' + z z').
__m128 dot4(__m128 ax, __m128 ay, __m128 az, __m128 aw, __m128 bx, __m128 by, __m128 bz, __m128 bw) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(aw, bw), _mm_mul_ps(ax, bx)),
                    _mm_add_ps(_mm_mul_ps(ay, by), _mm_mul_ps(az, bz)));
}

}  // namespace

void QuatBatch::flush() {
  __m128 ax = _mm_load_ps(&a_[0].x), ay = _mm_load_ps(&a_[1].x), az = _mm_load_ps(&a_[2].x), aw = _mm_load_ps(&a_[3].x);
  _MM_TRANSPOSE4_PS(ax, ay, az, aw);
  __m128 bx = _mm_load_ps(&b_[0].x), by = _mm_load_ps(&b_[1].x), bz = _mm_load_ps(&b_[2].x), bw = _mm_load_ps(&b_[3].x);
  _MM_TRANSPOSE4_PS(bx, by, bz, bw);
  // nlerp's flip: b = -b where dot(a, b) < 0 (negation is exact: a sign bit).
  const __m128 flip = _mm_and_ps(_mm_cmplt_ps(dot4(ax, ay, az, aw, bx, by, bz, bw), _mm_setzero_ps()),
                                 _mm_set1_ps(-0.0f));
  bx = _mm_xor_ps(bx, flip), by = _mm_xor_ps(by, flip), bz = _mm_xor_ps(bz, flip), bw = _mm_xor_ps(bw, flip);
  const __m128 wa = _mm_setr_ps(wa_[0], wa_[1], wa_[2], wa_[3]), wb = _mm_setr_ps(wb_[0], wb_[1], wb_[2], wb_[3]);
  const __m128 qx = _mm_add_ps(_mm_mul_ps(ax, wa), _mm_mul_ps(bx, wb));
  const __m128 qy = _mm_add_ps(_mm_mul_ps(ay, wa), _mm_mul_ps(by, wb));
  const __m128 qz = _mm_add_ps(_mm_mul_ps(az, wa), _mm_mul_ps(bz, wb));
  const __m128 qw = _mm_add_ps(_mm_mul_ps(aw, wa), _mm_mul_ps(bw, wb));
  // safeNormalize: hasDirection is len2 >= FLT_MIN and finite (both compares are
  // false for NaN); identity where it fails.
  const __m128 len2 = dot4(qx, qy, qz, qw, qx, qy, qz, qw);
  const __m128 ok = _mm_and_ps(_mm_cmpge_ps(len2, _mm_set1_ps(std::numeric_limits<float>::min())),
                               _mm_cmplt_ps(len2, _mm_set1_ps(std::numeric_limits<float>::infinity())));
  const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(len2));
  __m128 rx = _mm_and_ps(ok, _mm_mul_ps(qx, inv)), ry = _mm_and_ps(ok, _mm_mul_ps(qy, inv));
  __m128 rz = _mm_and_ps(ok, _mm_mul_ps(qz, inv));
  __m128 rw = _mm_or_ps(_mm_and_ps(ok, _mm_mul_ps(qw, inv)), _mm_andnot_ps(ok, _mm_set1_ps(1.0f)));
  _MM_TRANSPOSE4_PS(rx, ry, rz, rw);  // back to one quaternion (x, y, z, w as glm keeps them) per register
  const __m128 rows[4] = {rx, ry, rz, rw};
  static_assert(sizeof(glm::quat) == 16 && offsetof(glm::quat, x) == 0 && offsetof(glm::quat, w) == 12);
  for (int i = 0; i < count_; ++i) _mm_storeu_ps(&out_[i]->x, rows[i]);
  count_ = 0;
}
#else
void QuatBatch::flush() {
  for (int i = 0; i < count_; ++i) {
    const glm::quat a(a_[i].w, a_[i].x, a_[i].y, a_[i].z);
    glm::quat b(b_[i].w, b_[i].x, b_[i].y, b_[i].z);
    if (glm::dot(a, b) < 0.0f) b = -b;
    *out_[i] = safeNormalize(a * wa_[i] + b * wb_[i]);
  }
  count_ = 0;
}
#endif

}  // namespace engine
