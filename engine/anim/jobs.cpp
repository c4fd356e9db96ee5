#include "anim/jobs.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace engine {
namespace {

// Normal transform without an inverse: the cofactor matrix is the inverse
// transpose times the determinant, so after normalising it handles non-uniform
// scale, and a zero scale gives a zero vector instead of NaNs.
// r made unit length, or zero where it has none.
glm::vec3 unitOrZero(const glm::vec3& r) {
  const float len2 = glm::dot(r, r);
  return len2 > 0.0f ? r / std::sqrt(len2) : glm::vec3(0.0f);
}

#if !defined(__SSE2__)
glm::vec3 transformNormal(const glm::mat4& m, const glm::vec3& n) {
  glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  glm::mat3 cofactor(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1));
  return unitOrZero(cofactor * n);
}
#endif

bool usable(std::uint16_t joint, float weight, std::size_t paletteSize) {
  return weight != 0.0f && joint < paletteSize;
}

#if defined(__SSE2__)
// skinLinear's arithmetic on whole columns, one SSE register each, in glm's order
// element by element (the blend m += M_j w_j column by column; m * (p, 1) as
// (c0 x + c1 y) + (c2 z + c3); the cofactor columns as glm's cross products, then
// cofactor * n as (k0 x + k1 y) + k2 z): the same bits as the scalar loop, four
// lanes at a time (SkinningJob.LinearBlendIsGlmBitForBit holds them together).
struct Columns {
  __m128 c[4];
};

inline __m128 yzx(__m128 v) { return _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 0, 2, 1)); }
inline __m128 zxy(__m128 v) { return _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 1, 0, 2)); }
// glm::cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
inline __m128 cross(__m128 a, __m128 b) {
  return _mm_sub_ps(_mm_mul_ps(yzx(a), zxy(b)), _mm_mul_ps(yzx(b), zxy(a)));
}

void skinLinearSse(const SkinningJob& job) {
  const std::size_t k = static_cast<std::size_t>(job.influences);
  const bool withNormals = !job.normals.empty();
  const float* palette = &job.palette[0][0][0];
  for (std::size_t v = 0; v < job.positions.size(); ++v) {
    const std::uint16_t* joints = &job.joints[v * k];
    const float* weights = &job.weights[v * k];
    Columns m{{_mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps()}};
    for (std::size_t i = 0; i < k; ++i) {
      if (!usable(joints[i], weights[i], job.palette.size())) continue;
      const float* joint = palette + 16 * std::size_t(joints[i]);
      const __m128 w = _mm_set1_ps(weights[i]);
      for (int c = 0; c < 4; ++c) m.c[c] = _mm_add_ps(m.c[c], _mm_mul_ps(_mm_loadu_ps(joint + 4 * c), w));
    }
    const glm::vec3& p = job.positions[v];
    const __m128 xy = _mm_add_ps(_mm_mul_ps(m.c[0], _mm_set1_ps(p.x)), _mm_mul_ps(m.c[1], _mm_set1_ps(p.y)));
    const __m128 zw = _mm_add_ps(_mm_mul_ps(m.c[2], _mm_set1_ps(p.z)), m.c[3]);
    alignas(16) float out[4];
    _mm_store_ps(out, _mm_add_ps(xy, zw));
    job.outPositions[v] = glm::vec3(out[0], out[1], out[2]);
    if (!withNormals) continue;
    const glm::vec3& n = job.normals[v];
    const __m128 k0 = cross(m.c[1], m.c[2]), k1 = cross(m.c[2], m.c[0]), k2 = cross(m.c[0], m.c[1]);
    const __m128 r = _mm_add_ps(_mm_add_ps(_mm_mul_ps(k0, _mm_set1_ps(n.x)), _mm_mul_ps(k1, _mm_set1_ps(n.y))),
                                _mm_mul_ps(k2, _mm_set1_ps(n.z)));
    _mm_store_ps(out, r);
    job.outNormals[v] = unitOrZero(glm::vec3(out[0], out[1], out[2]));
  }
}
#endif

void skinLinear(const SkinningJob& job) {
#if defined(__SSE2__)
  skinLinearSse(job);
#else
  std::size_t k = static_cast<std::size_t>(job.influences);
  bool withNormals = !job.normals.empty();
  for (std::size_t v = 0; v < job.positions.size(); ++v) {
    const std::uint16_t* joints = &job.joints[v * k];
    const float* weights = &job.weights[v * k];
    glm::mat4 m(0.0f);
    for (std::size_t i = 0; i < k; ++i)
      if (usable(joints[i], weights[i], job.palette.size())) m += job.palette[joints[i]] * weights[i];
    job.outPositions[v] = glm::vec3(m * glm::vec4(job.positions[v], 1.0f));
    if (withNormals) job.outNormals[v] = transformNormal(m, job.normals[v]);
  }
#endif
}

void skinDualQuat(const SkinningJob& job) {
  std::size_t k = static_cast<std::size_t>(job.influences);
  bool withNormals = !job.normals.empty();
  for (std::size_t v = 0; v < job.positions.size(); ++v) {
    const std::uint16_t* joints = &job.joints[v * k];
    const float* weights = &job.weights[v * k];
    DualQuat sum{glm::quat(0.0f, 0.0f, 0.0f, 0.0f), glm::quat(0.0f, 0.0f, 0.0f, 0.0f)};
    bool first = true;
    for (std::size_t i = 0; i < k; ++i) {
      if (!usable(joints[i], weights[i], job.dualQuats.size())) continue;
      const DualQuat& dq = job.dualQuats[joints[i]];
      // The first influence sets the hemisphere the others are flipped into.
      if (first) {
        sum.real = dq.real * weights[i];
        sum.dual = dq.dual * weights[i];
        first = false;
      } else {
        accumulate(sum, dq, weights[i]);
      }
    }
    DualQuat n = normalize(sum);
    job.outPositions[v] = transformPoint(n, job.positions[v]);
    if (withNormals) job.outNormals[v] = n.real * job.normals[v];
  }
}

#if defined(__SSE2__)
// toMatrix of four joints at once, one joint per SSE lane (SoA), then each
// parent * local product as timesAffine sums it: its bits, without a 4x4 local
// matrix built per joint in scalar code.
class LocalMatrices4 {
 public:
  explicit LocalMatrices4(const Srt* srt) {
    static_assert(sizeof(Srt) == 40 && offsetof(Srt, rotation) == 12 && offsetof(Srt, translation) == 28);
    static_assert(offsetof(glm::quat, x) == 0 && offsetof(glm::quat, w) == 12);
    // Each load stays inside its Srt: the scale with rotation.x, the translation
    // after rotation.w.
    __m128 sx = _mm_loadu_ps(&srt[0].scale.x), sy = _mm_loadu_ps(&srt[1].scale.x);
    __m128 sz = _mm_loadu_ps(&srt[2].scale.x), s3 = _mm_loadu_ps(&srt[3].scale.x);
    _MM_TRANSPOSE4_PS(sx, sy, sz, s3);
    __m128 qx = _mm_loadu_ps(&srt[0].rotation.x), qy = _mm_loadu_ps(&srt[1].rotation.x);
    __m128 qz = _mm_loadu_ps(&srt[2].rotation.x), qw = _mm_loadu_ps(&srt[3].rotation.x);
    _MM_TRANSPOSE4_PS(qx, qy, qz, qw);
    __m128 t0 = _mm_loadu_ps(&srt[0].rotation.w), tx = _mm_loadu_ps(&srt[1].rotation.w);
    __m128 ty = _mm_loadu_ps(&srt[2].rotation.w), tz = _mm_loadu_ps(&srt[3].rotation.w);
    _MM_TRANSPOSE4_PS(t0, tx, ty, tz);
    // glm::mat3_cast, lane by lane.
    const __m128 one = _mm_set1_ps(1.0f), two = _mm_set1_ps(2.0f);
    const __m128 qxx = _mm_mul_ps(qx, qx), qyy = _mm_mul_ps(qy, qy), qzz = _mm_mul_ps(qz, qz);
    const __m128 qxz = _mm_mul_ps(qx, qz), qxy = _mm_mul_ps(qx, qy), qyz = _mm_mul_ps(qy, qz);
    const __m128 qwx = _mm_mul_ps(qw, qx), qwy = _mm_mul_ps(qw, qy), qwz = _mm_mul_ps(qw, qz);
    // toMatrix: column c is rotation column c times scale c.
    store(0, _mm_mul_ps(_mm_sub_ps(one, _mm_mul_ps(two, _mm_add_ps(qyy, qzz))), sx));
    store(1, _mm_mul_ps(_mm_mul_ps(two, _mm_add_ps(qxy, qwz)), sx));
    store(2, _mm_mul_ps(_mm_mul_ps(two, _mm_sub_ps(qxz, qwy)), sx));
    store(3, _mm_mul_ps(_mm_mul_ps(two, _mm_sub_ps(qxy, qwz)), sy));
    store(4, _mm_mul_ps(_mm_sub_ps(one, _mm_mul_ps(two, _mm_add_ps(qxx, qzz))), sy));
    store(5, _mm_mul_ps(_mm_mul_ps(two, _mm_add_ps(qyz, qwx)), sy));
    store(6, _mm_mul_ps(_mm_mul_ps(two, _mm_add_ps(qxz, qwy)), sz));
    store(7, _mm_mul_ps(_mm_mul_ps(two, _mm_sub_ps(qyz, qwx)), sz));
    store(8, _mm_mul_ps(_mm_sub_ps(one, _mm_mul_ps(two, _mm_add_ps(qxx, qyy))), sz));
    store(9, tx), store(10, ty), store(11, tz);
  }

  // parent * (lane `j`'s local matrix), timesAffine's sums.
  Columns times(const Columns& parent, std::size_t j) const {
    const __m128 *p = parent.c;
    const auto term = [&](int column, int row) { return _mm_mul_ps(p[row], _mm_set1_ps(m_[3 * column + row][j])); };
    Columns out;
    for (int c = 0; c < 3; ++c) out.c[c] = _mm_add_ps(_mm_add_ps(term(c, 0), term(c, 1)), term(c, 2));
    out.c[3] = _mm_add_ps(_mm_add_ps(term(3, 0), term(3, 1)), _mm_add_ps(term(3, 2), p[3]));
    return out;
  }

 private:
  void store(int element, __m128 lanes) { _mm_store_ps(m_[element], lanes); }
  alignas(16) float m_[12][4];  // the 3x4 local matrices, column-major, element-major
};
#endif

// The layers of either blending job fit when each has one entry per output
// (`entries` of the layer) and a finite weight >= 0.
template <typename Layer, typename Entries>
bool layersFit(std::span<const Layer> layers, std::size_t outputs, Entries entries) {
  for (const Layer& layer : layers)
    if (entries(layer).size() != outputs || !(layer.weight >= 0.0f) || !std::isfinite(layer.weight)) return false;
  return true;
}

// The layers' weights are normalised by their sum; below this the rest is written.
template <typename Layer>
float totalWeight(std::span<const Layer> layers) {
  float total = 0.0f;
  for (const Layer& layer : layers) total += layer.weight;
  return total;
}
constexpr float kNoWeight = 1e-6f;

// Morph deltas fit when absent or one per vertex per target.
bool deltasFit(std::size_t deltas, std::size_t vertices, std::size_t targets) {
  return deltas == 0 || deltas == vertices * targets;
}

// One attribute of MorphJob: out = base + sum_t w_t * delta_t, target by target.
template <typename Vec>
void morphAttribute(std::span<const Vec> base, std::span<const glm::vec3> deltas, std::span<const float> weights,
                    std::span<Vec> out) {
  if (out.data() != base.data()) std::copy(base.begin(), base.end(), out.begin());
  if (deltas.empty()) return;
  const std::size_t n = base.size();
  for (std::size_t t = 0; t < weights.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const glm::vec3* d = deltas.data() + t * n;
    for (std::size_t v = 0; v < n; ++v) {
      glm::vec3 moved = glm::vec3(out[v]) + w * d[v];
      out[v].x = moved.x;
      out[v].y = moved.y;
      out[v].z = moved.z;
    }
  }
}

}  // namespace

bool MorphSamplingJob::validate() const {
  if (clip == nullptr || !std::isfinite(time) || output.size() != restWeights.size()) return false;
  for (const MorphTrack& track : clip->morphTracks())
    if (track.first < 0 || static_cast<std::size_t>(track.first) + static_cast<std::size_t>(track.targets) > output.size())
      return false;
  return true;
}

bool MorphSamplingJob::run() const {
  if (!validate()) return false;
  std::copy(restWeights.begin(), restWeights.end(), output.begin());
  const std::span<const MorphTrack> tracks = clip->morphTracks();
  if (context) context->bind(*clip);
  const std::span<KeyCursor> cursors = context ? context->morphCursors() : std::span<KeyCursor>{};
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const MorphTrack& track = tracks[i];
    const auto out = output.subspan(static_cast<std::size_t>(track.first), static_cast<std::size_t>(track.targets));
    if (context) {
      sampleWeights(track, time, out, cursors[i]);
    } else {
      sampleWeights(track, time, out);
    }
  }
  return true;
}

bool MorphBlendingJob::validate() const {
  return output.size() == restWeights.size() &&
         layersFit(layers, output.size(), [](const Layer& layer) { return layer.weights; });
}

bool MorphBlendingJob::run() const {
  if (!validate()) return false;
  const float total = totalWeight(layers);
  if (total < kNoWeight) {
    std::copy(restWeights.begin(), restWeights.end(), output.begin());
    return true;
  }
  std::fill(output.begin(), output.end(), 0.0f);
  for (const Layer& layer : layers) {
    const float w = layer.weight / total;
    for (std::size_t i = 0; i < output.size(); ++i) output[i] += layer.weights[i] * w;
  }
  return true;
}

bool MorphJob::validate() const {
  const std::size_t n = positions.size(), targets = weights.size();
  if (outPositions.size() != n || !deltasFit(positionDeltas.size(), n, targets)) return false;
  if (!normals.empty() && (normals.size() != n || outNormals.size() != n || !deltasFit(normalDeltas.size(), n, targets)))
    return false;
  if (!tangents.empty() &&
      (tangents.size() != n || outTangents.size() != n || !deltasFit(tangentDeltas.size(), n, targets)))
    return false;
  return true;
}

bool MorphJob::run() const {
  if (!validate()) return false;
  morphAttribute<glm::vec3>(positions, positionDeltas, weights, outPositions);
  if (!normals.empty()) morphAttribute<glm::vec3>(normals, normalDeltas, weights, outNormals);
  if (!tangents.empty()) morphAttribute<glm::vec4>(tangents, tangentDeltas, weights, outTangents);
  return true;
}

bool SamplingJob::validate() const {
  return clip != nullptr && std::isfinite(time) && output.size() == restPose.size() &&
         clip->jointsDriven() <= output.size();
}

bool SamplingJob::run() const {
  if (!validate()) return false;
  if (context != nullptr && clip->grouped()) {
    // The rest pose only where a part keeps it: sampleTracks writes every part of
    // the fully driven joints (RiggedFigure: 19 of its 22 nodes).
    for (const std::uint32_t j : clip->partlyDrivenJoints()) output[j] = restPose[j];
    std::copy(restPose.begin() + std::ptrdiff_t(clip->jointsDriven()), restPose.end(),
              output.begin() + std::ptrdiff_t(clip->jointsDriven()));
  } else {
    std::copy(restPose.begin(), restPose.end(), output.begin());
  }
  const std::span<const Track> tracks = clip->tracks();
  if (context == nullptr) {
    for (const Track& track : tracks) applyTrack(track, time, output[static_cast<std::size_t>(track.joint)], rotations);
    return true;
  }
  sampleTracks(*clip, time, output, rotations, *context);
  return true;
}

bool BlendingJob::validate() const {
  return output.size() == restPose.size() &&
         layersFit(layers, output.size(), [](const Layer& layer) { return layer.pose; });
}

bool BlendingJob::run() const {
  if (!validate()) return false;
  const float total = totalWeight(layers);
  if (total < kNoWeight) {
    std::copy(restPose.begin(), restPose.end(), output.begin());
    return true;
  }
  for (std::size_t j = 0; j < output.size(); ++j) {
    Srt out{glm::vec3(0.0f), glm::quat(0.0f, 0.0f, 0.0f, 0.0f), glm::vec3(0.0f)};
    bool first = true;
    for (const Layer& layer : layers) {
      if (layer.weight == 0.0f) continue;
      float w = layer.weight / total;
      const Srt& in = layer.pose[j];
      out.translation += in.translation * w;
      out.scale += in.scale * w;
      // Flip into the first layer's hemisphere so opposite signs do not cancel.
      float sign = (!first && glm::dot(out.rotation, in.rotation) < 0.0f) ? -1.0f : 1.0f;
      out.rotation += in.rotation * (w * sign);
      first = false;
    }
    out.rotation = safeNormalize(out.rotation);
    output[j] = out;
  }
  return true;
}

bool LocalToModelJob::validate() const {
  if (locals.size() != parents.size() || models.size() != parents.size() || fixed.size() > parents.size())
    return false;
  if (parents.size() > std::numeric_limits<std::uint32_t>::max()) return false;
  // -1 <= parents[i] < i as one unsigned compare, without an early exit, so that the
  // compiler tests four parents at a time: run() validates every call, and a branch
  // per joint was a tenth of its time.
  std::uint32_t bad = 0;
  const std::uint32_t n = static_cast<std::uint32_t>(parents.size());
  for (std::uint32_t i = 0; i < n; ++i) bad |= static_cast<std::uint32_t>(parents[i] + 1) > i;
  return bad == 0;
}

bool LocalToModelJob::run() const {
  if (!validate()) return false;
  std::copy(fixed.begin(), fixed.end(), models.begin());
  const std::size_t first = fixed.size();
#if defined(__SSE2__)
  // Depth-first order makes a joint's parent most often the joint before it: its
  // matrix is taken from the registers it was computed in, not reloaded from the
  // store just made, so a chain of joints waits on arithmetic only.
  const auto load = [](const glm::mat4& m) {
    return Columns{{_mm_loadu_ps(&m[0][0]), _mm_loadu_ps(&m[1][0]), _mm_loadu_ps(&m[2][0]), _mm_loadu_ps(&m[3][0])}};
  };
  Columns last = first > 0 ? load(models[first - 1]) : Columns{};
  // Joints i .. i + n - 1, whose locals are srt[0 .. n - 1].
  const auto block = [&](const Srt* srt, std::size_t i, std::size_t n) {
    const LocalMatrices4 local(srt);
    for (std::size_t j = 0; j < n; ++j) {
      const int parent = parents[i + j];
      const Columns p = parent >= 0 && std::size_t(parent) + 1 == i + j ? last
                        : load(parent < 0 ? root : models[std::size_t(parent)]);
      last = local.times(p, j);
      for (int c = 0; c < 4; ++c) _mm_storeu_ps(&models[i + j][c][0], last.c[c]);
    }
  };
  std::size_t i = first;
  for (; i + 4 <= parents.size(); i += 4) block(&locals[i], i, 4);
  if (i < parents.size()) {
    Srt tail[4];  // the last joints, padded with identities
    std::copy(locals.begin() + std::ptrdiff_t(i), locals.end(), tail);
    block(tail, i, parents.size() - i);
  }
#else
  for (std::size_t i = first; i < parents.size(); ++i)
    models[i] = timesAffine(parents[i] < 0 ? root : models[std::size_t(parents[i])], toMatrix(locals[i]));
#endif
  return true;
}

bool SkinningPaletteJob::validate() const {
  if (joints.size() != inverseBinds.size() || palette.size() != joints.size()) return false;
  for (int j : joints)
    if (j < 0 || static_cast<std::size_t>(j) >= models.size()) return false;
  return true;
}

bool SkinningPaletteJob::run() const {
  if (!validate()) return false;
  for (std::size_t k = 0; k < joints.size(); ++k)
    palette[k] = models[static_cast<std::size_t>(joints[k])] * inverseBinds[k];
  return true;
}

bool DualQuatPaletteJob::validate() const { return output.size() == palette.size(); }

bool DualQuatPaletteJob::run() const {
  if (!validate()) return false;
  for (std::size_t k = 0; k < palette.size(); ++k) output[k] = makeDualQuat(palette[k]);
  return true;
}

bool SkinningJob::validate() const {
  if (influences < 1 || influences > 8) return false;
  std::size_t count = positions.size();
  std::size_t k = static_cast<std::size_t>(influences);
  if (joints.size() != count * k || weights.size() != count * k) return false;
  if (outPositions.size() != count) return false;
  if (!normals.empty() && (normals.size() != count || outNormals.size() != count)) return false;
  return method == SkinningMethod::Linear ? !palette.empty() : !dualQuats.empty();
}

bool SkinningJob::run() const {
  if (!validate()) return false;
  if (method == SkinningMethod::Linear) {
    skinLinear(*this);
  } else {
    skinDualQuat(*this);
  }
  return true;
}

}  // namespace engine
