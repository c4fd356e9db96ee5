#pragma once
// PinholeCamera's rays for eight image points at once (AVX2): generateRay<float> and
// clippedToFarPlane lane by lane, their double arithmetic in its order, so that each
// ray is the scalar camera's bit for bit. Internal to the ray tracer (the Whitted
// tracer's packets, the path tracer's spans); callers check the CPU has AVX2.
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "raytrace/avx2_region.h"
#include "raytrace/camera.h"

namespace engine::rt {

ENGINE_AVX2_BEGIN
namespace lanes8 {

// PinholeCamera::generateRay<float> and clippedToFarPlane for four lanes, in double as
// they are: the direction rounded once to float, the far plane's t from that float.
inline void cameraQuad(const PinholeCamera& c, const double* px, const double* py, float* d[3], float* tMax) {
  using D = __m256d;
  const D one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
  const D x = _mm256_mul_pd(
      _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(two, _mm256_loadu_pd(px)), _mm256_set1_pd(double(c.width()))), one),
      _mm256_set1_pd(c.xScale()));
  const D yUnscaled =
      _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(two, _mm256_loadu_pd(py)), _mm256_set1_pd(double(c.height()))), one);
  const D y = _mm256_mul_pd(_mm256_xor_pd(_mm256_set1_pd(-0.0), yUnscaled), _mm256_set1_pd(c.yScale()));
  // glm::normalize(dvec3(x, y, 1)): v * (1 / sqrt(dot(v, v))).
  const D inv = _mm256_div_pd(
      one, _mm256_sqrt_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(one, one))));
  const D lx = _mm256_mul_pd(x, inv), ly = _mm256_mul_pd(y, inv), lz = _mm256_mul_pd(one, inv);
  D depth = _mm256_setzero_pd();
  for (int a = 0; a < 3; ++a) {
    const D world = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(lx, _mm256_set1_pd(c.right()[a])),
                                                _mm256_mul_pd(ly, _mm256_set1_pd(c.up()[a]))),
                                  _mm256_mul_pd(lz, _mm256_set1_pd(c.forward()[a])));
    const __m128 rounded = _mm256_cvtpd_ps(world);
    _mm_storeu_ps(d[a], rounded);
    const D term = _mm256_mul_pd(_mm256_cvtps_pd(rounded), _mm256_set1_pd(c.forward()[a]));
    depth = a == 0 ? term : _mm256_add_pd(depth, term);
  }
  const __m128 clipped = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(c.farPlane()), depth));
  // depth > 0 in 64-bit lanes, packed to 32-bit ones.
  const __m256i ahead64 = _mm256_castpd_si256(_mm256_cmp_pd(depth, _mm256_setzero_pd(), _CMP_GT_OQ));
  const __m128 ahead = _mm_castsi128_ps(
      _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(ahead64, _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0))));
  _mm_storeu_ps(tMax, _mm_blendv_ps(_mm_set1_ps(std::numeric_limits<float>::infinity()), clipped, ahead));
}

// The rays through (px[i], py[i]), i < 8: directions d and tMax per lane (the origin is
// the camera's position in float for all).
inline void cameraRays(const PinholeCamera& camera, const double* px, const double* py, float* dx, float* dy,
                       float* dz, float* tMax) {
  for (int half = 0; half < 2; ++half) {
    float* d[3] = {dx + 4 * half, dy + 4 * half, dz + 4 * half};
    cameraQuad(camera, px + 4 * half, py + 4 * half, d, tMax + 4 * half);
  }
}

// cameraRays for n points, eight at a time (the last eight padded with the first point).
inline void cameraRays(const PinholeCamera& camera, const double* px, const double* py, std::size_t n, float* dx,
                       float* dy, float* dz, float* tMax) {
  for (std::size_t first = 0; first < n; first += 8) {
    alignas(32) double x[8], y[8];
    alignas(32) float d[3][8], t[8];
    const std::size_t count = std::min<std::size_t>(8, n - first);
    for (std::size_t i = 0; i < 8; ++i) x[i] = px[first + (i < count ? i : 0)], y[i] = py[first + (i < count ? i : 0)];
    cameraRays(camera, x, y, d[0], d[1], d[2], t);
    for (std::size_t i = 0; i < count; ++i) {
      dx[first + i] = d[0][i], dy[first + i] = d[1][i], dz[first + i] = d[2][i], tMax[first + i] = t[i];
    }
  }
}

}  // namespace lanes8
ENGINE_AVX2_END

}  // namespace engine::rt
