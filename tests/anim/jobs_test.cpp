// Local-to-model, palettes and CPU skinning against double-precision references
// and hand-computed values, plus every invalid job set-up.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "anim/jobs.h"
#include "anim/skeleton.h"

namespace engine {
namespace {

glm::dmat4 toMatrixD(const Srt& srt) {
  glm::dquat q(srt.rotation.w, srt.rotation.x, srt.rotation.y, srt.rotation.z);
  glm::dmat3 r = glm::mat3_cast(q);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(r[0] * double(srt.scale.x), 0.0);
  m[1] = glm::dvec4(r[1] * double(srt.scale.y), 0.0);
  m[2] = glm::dvec4(r[2] * double(srt.scale.z), 0.0);
  m[3] = glm::dvec4(glm::dvec3(srt.translation), 1.0);
  return m;
}

// Runs LocalToModelJob and a double reference on the same hierarchy; returns the
// largest distance between the joints' model-space origins.
double originError(const std::vector<int>& parents, const std::vector<Srt>& locals) {
  std::vector<glm::mat4> models(parents.size());
  LocalToModelJob job{parents, locals, glm::mat4(1.0f), models};
  EXPECT_TRUE(job.run());
  std::vector<glm::dmat4> ref(parents.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < parents.size(); ++i) {
    ref[i] = parents[i] < 0 ? toMatrixD(locals[i]) : ref[static_cast<std::size_t>(parents[i])] * toMatrixD(locals[i]);
    worst = std::max(worst, glm::distance(glm::dvec3(ref[i][3]), glm::dvec3(glm::vec3(models[i][3]))));
  }
  return worst;
}

TEST(LocalToModel, ThousandBoneChainMatchesDoubleReference) {
  const int n = 1000;
  std::vector<int> parents;
  std::vector<Srt> locals;
  for (int i = 0; i < n; ++i) {
    parents.push_back(i - 1);
    glm::vec3 axis = glm::normalize(glm::vec3(std::sin(i * 0.7f), 1.0f, std::cos(i * 1.3f)));
    locals.push_back(Srt{glm::vec3(1.0f), glm::angleAxis(0.05f, axis), glm::vec3(0, 1, 0)});
  }
  // The chain spans up to 1000 units; float keeps ~1e-7 relative per product.
  EXPECT_LT(originError(parents, locals), 1000 * 2e-5);
}

TEST(LocalToModel, FanOf256BonesMatchesDoubleReference) {
  std::vector<int> parents{-1};
  std::vector<Srt> locals{Srt{glm::vec3(2.0f), glm::angleAxis(0.3f, glm::vec3(0, 0, 1)), glm::vec3(5, 0, 0)}};
  for (int i = 0; i < 256; ++i) {
    parents.push_back(0);
    float a = i * 0.0245f;
    locals.push_back(Srt{glm::vec3(1.0f), glm::angleAxis(a, glm::vec3(0, 1, 0)),
                         glm::vec3(std::cos(a) * 3, 0.1f * i, std::sin(a) * 3)});
  }
  EXPECT_LT(originError(parents, locals), 1e-4);
}

TEST(LocalToModel, NonUniformAndZeroScale) {
  std::vector<int> parents{-1, 0, 1};
  std::vector<Srt> locals{
      Srt{glm::vec3(2, 1, 0.5f), glm::angleAxis(0.4f, glm::vec3(1, 0, 0)), glm::vec3(1, 2, 3)},
      Srt{glm::vec3(1, 3, 1), glm::angleAxis(1.1f, glm::vec3(0, 1, 0)), glm::vec3(0, 1, 1)},
      Srt{glm::vec3(0, 1, 1), glm::quat(1, 0, 0, 0), glm::vec3(1, 1, 1)}};
  EXPECT_LT(originError(parents, locals), 1e-5);
  // A zero-scaled joint still gives finite matrices, and skinning through it
  // gives finite (zero) normals rather than NaNs.
  std::vector<glm::mat4> models(3);
  ASSERT_TRUE((LocalToModelJob{parents, locals, glm::mat4(1.0f), models}.run()));
  std::vector<glm::vec3> pos{{1, 1, 1}}, nrm{{1, 0, 0}}, outP(1), outN(1);
  std::vector<std::uint16_t> joints{2, 0, 0, 0};
  std::vector<float> weights{1, 0, 0, 0};
  SkinningJob skin;
  skin.positions = pos;
  skin.normals = nrm;
  skin.joints = joints;
  skin.weights = weights;
  skin.palette = models;
  skin.outPositions = outP;
  skin.outNormals = outN;
  ASSERT_TRUE(skin.run());
  EXPECT_TRUE(std::isfinite(outP[0].x) && std::isfinite(outN[0].x));
}

// The job builds local matrices four at a time (SSE where there is SSE) and keeps
// the parent in registers when it is the joint before; it must give the bits of
// timesAffine(parent, toMatrix(local)), under a root that is not the identity, with
// negative, non-uniform and zero scales, parents before and right before.
TEST(LocalToModel, SameBitsAsTheScalarProduct) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  const glm::mat4 root = glm::translate(glm::mat4(1.0f), glm::vec3(1, -2, 3)) *
                         glm::mat4_cast(glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  // Every length of a last block of fours, and one long skeleton.
  for (const int count : {1, 2, 3, 4, 5, 6, 7, 8, 203}) {
    std::vector<int> parents;
    std::vector<Srt> locals;
    for (int i = 0; i < count; ++i) {
      parents.push_back(i == 0 || i % 37 == 0 ? -1 : i % 3 == 0 ? i - 1 : int(rng() % unsigned(i)));
      const glm::quat q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
      glm::vec3 scale(u(rng), u(rng), u(rng));
      if (i % 11 == 0) scale.y = 0.0f;
      locals.push_back(Srt{scale, q, glm::vec3(u(rng), u(rng), u(rng))});
    }
    std::vector<glm::mat4> models(parents.size()), expected(parents.size());
    ASSERT_TRUE((LocalToModelJob{parents, locals, root, models}.run()));
    for (std::size_t i = 0; i < parents.size(); ++i) {
      expected[i] = timesAffine(parents[i] < 0 ? root : expected[std::size_t(parents[i])], toMatrix(locals[i]));
      EXPECT_EQ(std::memcmp(&models[i], &expected[i], sizeof(glm::mat4)), 0) << count << " joints, joint " << i;
    }
  }
}

// A fixed prefix is copied, and the joints after it are computed from it: given the
// full job's own first K matrices, every K gives the full job's bits; given other
// matrices, the descendants follow those.
TEST(LocalToModel, FixedPrefixIsCopiedAndTheRestBuiltOnIt) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  std::vector<int> parents;
  std::vector<Srt> locals;
  for (int i = 0; i < 23; ++i) {
    parents.push_back(i == 0 ? -1 : i % 4 == 0 ? int(rng() % unsigned(i)) : i - 1);
    locals.push_back(Srt{glm::vec3(u(rng), u(rng), u(rng)), glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng))),
                         glm::vec3(u(rng), u(rng), u(rng))});
  }
  const glm::mat4 root = glm::translate(glm::mat4(1.0f), glm::vec3(3, 1, -2));
  std::vector<glm::mat4> full(parents.size()), models(parents.size());
  ASSERT_TRUE((LocalToModelJob{parents, locals, root, full}.run()));
  for (std::size_t k = 0; k <= parents.size(); ++k) {
    std::fill(models.begin(), models.end(), glm::mat4(0.0f));
    ASSERT_TRUE((LocalToModelJob{parents, locals, root, models, std::span(full).first(k)}.run()));
    EXPECT_EQ(std::memcmp(models.data(), full.data(), full.size() * sizeof(glm::mat4)), 0) << k << " fixed";
  }
  // The first two joints fixed elsewhere: joint 2 (child of 1) is built on joint 1's.
  const std::vector<glm::mat4> moved{glm::mat4(2.0f), glm::translate(glm::mat4(1.0f), glm::vec3(7, 0, 0))};
  ASSERT_TRUE((LocalToModelJob{parents, locals, root, models, moved}.run()));
  EXPECT_EQ(models[1], moved[1]);
  const glm::mat4 expected = timesAffine(moved[1], toMatrix(locals[2]));
  EXPECT_EQ(std::memcmp(&models[2], &expected, sizeof(glm::mat4)), 0);
  std::vector<glm::mat4> tooMany(parents.size() + 1);
  EXPECT_FALSE((LocalToModelJob{parents, locals, root, models, tooMany}.validate()));
}

TEST(LocalToModel, ValidateRejectsChildrenBeforeParents) {
  std::vector<int> parents{1, -1};
  std::vector<Srt> locals(2);
  std::vector<glm::mat4> models(2), few(1);
  EXPECT_FALSE((LocalToModelJob{parents, locals, glm::mat4(1.0f), models}.validate()));
  std::vector<int> good{-1, 0};
  EXPECT_TRUE((LocalToModelJob{good, locals, glm::mat4(1.0f), models}.validate()));
  EXPECT_FALSE((LocalToModelJob{good, locals, glm::mat4(1.0f), few}.validate()));
}

TEST(Skeleton, OrdersParentsFirstAndMapsIndices) {
  // Raw order: child before parent, two roots.
  RawSkeleton raw{{2, -1, 1, -1}, std::vector<Srt>(4), {"c", "root", "mid", "other"}};
  auto s = Skeleton::build(raw);
  ASSERT_TRUE(s.ok());
  for (int j = 0; j < s->jointCount(); ++j) EXPECT_LT(s->parents()[static_cast<std::size_t>(j)], j);
  for (int r = 0; r < 4; ++r) EXPECT_EQ(s->rawOfJoint(s->jointOfRaw(r)), r);
  EXPECT_EQ(s->name(s->jointOfRaw(2)), "mid");
  EXPECT_FALSE(Skeleton::build(RawSkeleton{{1, 0}, std::vector<Srt>(2), {}}).ok());  // cycle
  EXPECT_FALSE(Skeleton::build(RawSkeleton{{5}, std::vector<Srt>(1), {}}).ok());     // bad parent
  EXPECT_FALSE(Skeleton::build(RawSkeleton{{-1}, {}, {}}).ok());                    // no rest pose
}

TEST(SkinningPalette, IsModelTimesInverseBind) {
  std::vector<glm::mat4> models{toMatrix(Srt{glm::vec3(1), glm::quat(1, 0, 0, 0), glm::vec3(0, 2, 0)})};
  std::vector<int> joints{0};
  std::vector<glm::mat4> inverseBinds{toMatrix(Srt{glm::vec3(1), glm::quat(1, 0, 0, 0), glm::vec3(0, -1, 0)})};
  std::vector<glm::mat4> palette(1);
  ASSERT_TRUE((SkinningPaletteJob{models, joints, inverseBinds, palette}.run()));
  EXPECT_EQ(glm::vec3(palette[0][3]), glm::vec3(0, 1, 0));
  std::vector<int> bad{3};
  EXPECT_FALSE((SkinningPaletteJob{models, bad, inverseBinds, palette}.validate()));
  std::vector<glm::mat4> none;
  EXPECT_FALSE((SkinningPaletteJob{models, joints, none, palette}.validate()));
}

SkinningJob makeJob(SkinningMethod method, int influences, const std::vector<glm::vec3>& pos,
                    const std::vector<std::uint16_t>& joints, const std::vector<float>& weights,
                    const std::vector<glm::mat4>& palette, const std::vector<DualQuat>& dqs,
                    std::vector<glm::vec3>& out) {
  SkinningJob job;
  job.method = method;
  job.influences = influences;
  job.positions = pos;
  job.joints = joints;
  job.weights = weights;
  job.palette = palette;
  job.dualQuats = dqs;
  job.outPositions = out;
  return job;
}

TEST(Skinning, ValidateRejectsMismatchedSpans) {
  std::vector<glm::vec3> pos(2), out(2), shortOut(1);
  std::vector<std::uint16_t> joints(8, 0);
  std::vector<float> weights(8, 0.25f);
  std::vector<glm::mat4> palette(1, glm::mat4(1.0f));
  std::vector<DualQuat> dqs(1);
  EXPECT_TRUE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, dqs, out).validate());
  EXPECT_FALSE(makeJob(SkinningMethod::Linear, 8, pos, joints, weights, palette, dqs, out).validate());
  EXPECT_FALSE(makeJob(SkinningMethod::Linear, 0, pos, joints, weights, palette, dqs, out).validate());
  EXPECT_FALSE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, dqs, shortOut).validate());
  EXPECT_FALSE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, {}, dqs, out).validate());
  EXPECT_FALSE(makeJob(SkinningMethod::DualQuat, 4, pos, joints, weights, palette, {}, out).validate());
  SkinningJob withNormals = makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, dqs, out);
  withNormals.normals = pos;  // normals without an output for them
  EXPECT_FALSE(withNormals.validate());
}

// Linear blend skinning is glm's formula to the bit, whichever code runs it (the
// job's SSE columns on x86): m = sum of M_j w_j over the usable influences, the
// position m (p, 1), the normal the cofactor of m's 3x3 times n, made unit. Random
// palettes with scale and shear, 1 to 8 influences with zero weights and joints past
// the palette among them, over 200k vertices.
TEST(Skinning, LinearBlendIsGlmBitForBit) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  std::vector<glm::mat4> palette(40);
  for (glm::mat4& m : palette)
    for (int c = 0; c < 4; ++c) m[c] = glm::vec4(u(rng), u(rng), u(rng), c == 3 ? 1.0f : 0.0f);
  for (const int k : {1, 4, 8}) {
    const std::size_t vertices = 200000 / 3;
    std::vector<glm::vec3> pos(vertices), nrm(vertices), outP(vertices), outN(vertices);
    std::vector<std::uint16_t> joints(vertices * std::size_t(k));
    std::vector<float> weights(joints.size());
    for (std::size_t v = 0; v < vertices; ++v) {
      pos[v] = glm::vec3(u(rng), u(rng), u(rng)) * 50.0f;
      nrm[v] = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
      for (std::size_t i = 0; i < std::size_t(k); ++i) {
        joints[v * std::size_t(k) + i] = std::uint16_t(rng() % 44);  // a few past the palette
        weights[v * std::size_t(k) + i] = rng() % 5 == 0 ? 0.0f : std::abs(u(rng)) * 0.5f;
      }
    }
    SkinningJob job = makeJob(SkinningMethod::Linear, k, pos, joints, weights, palette, {}, outP);
    job.normals = nrm;
    job.outNormals = outN;
    ASSERT_TRUE(job.run());
    for (std::size_t v = 0; v < vertices; ++v) {
      glm::mat4 m(0.0f);
      for (std::size_t i = 0; i < std::size_t(k); ++i) {
        const std::uint16_t j = joints[v * std::size_t(k) + i];
        const float w = weights[v * std::size_t(k) + i];
        if (w != 0.0f && j < palette.size()) m += palette[j] * w;
      }
      const glm::vec3 p(m * glm::vec4(pos[v], 1.0f));
      const glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
      const glm::vec3 r = glm::mat3(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1)) * nrm[v];
      const float len2 = glm::dot(r, r);
      const glm::vec3 n = len2 > 0.0f ? r / std::sqrt(len2) : glm::vec3(0.0f);
      ASSERT_EQ(std::memcmp(&outP[v], &p, sizeof p), 0) << "k " << k << ", vertex " << v;
      ASSERT_EQ(std::memcmp(&outN[v], &n, sizeof n), 0) << "k " << k << ", vertex " << v;
    }
  }
}

TEST(Skinning, EightInfluencesMatchAHandSum) {
  std::vector<glm::mat4> palette;
  for (int j = 0; j < 8; ++j)
    palette.push_back(toMatrix(Srt{glm::vec3(1.0f + j * 0.1f), glm::angleAxis(j * 0.2f, glm::vec3(0, 0, 1)),
                                   glm::vec3(j, 0, 0)}));
  std::vector<glm::vec3> pos{{1, 2, 3}}, out(1);
  std::vector<std::uint16_t> joints{0, 1, 2, 3, 4, 5, 6, 7};
  std::vector<float> weights{0.3f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f};
  ASSERT_TRUE(makeJob(SkinningMethod::Linear, 8, pos, joints, weights, palette, {}, out).run());
  glm::vec3 expected(0.0f);
  for (int j = 0; j < 8; ++j) expected += weights[static_cast<std::size_t>(j)] * glm::vec3(palette[static_cast<std::size_t>(j)] * glm::vec4(pos[0], 1));
  EXPECT_LT(glm::distance(out[0], expected), 1e-5f);
}

TEST(Skinning, WeightsThatDoNotSumToOneScaleTheResult) {
  // The loader normalises weights; the job takes them as given, so a sum of 0.5
  // halves the position. This pins the contract down.
  std::vector<glm::mat4> palette{glm::mat4(1.0f)};
  std::vector<glm::vec3> pos{{2, 4, 6}}, out(1);
  std::vector<std::uint16_t> joints{0, 0, 0, 0};
  std::vector<float> weights{0.25f, 0.25f, 0.0f, 0.0f};
  ASSERT_TRUE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, {}, out).run());
  EXPECT_EQ(out[0], glm::vec3(1, 2, 3));
}

TEST(Skinning, PaddingJointsPastThePaletteAreIgnored) {
  std::vector<glm::mat4> palette{glm::mat4(1.0f)};
  std::vector<glm::vec3> pos{{2, 4, 6}}, out(1);
  std::vector<std::uint16_t> joints{0, 900, 0, 0};
  std::vector<float> weights{1.0f, 0.0f, 0.0f, 0.0f};
  ASSERT_TRUE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, {}, out).run());
  EXPECT_EQ(out[0], pos[0]);
}

TEST(Skinning, DualQuatMatchesLinearForRigidSingleInfluence) {
  std::vector<glm::mat4> palette{
      toMatrix(Srt{glm::vec3(1), glm::angleAxis(1.2f, glm::normalize(glm::vec3(1, 1, 0))), glm::vec3(1, 2, 3)}),
      toMatrix(Srt{glm::vec3(1), glm::angleAxis(-0.4f, glm::vec3(0, 0, 1)), glm::vec3(-1, 0, 0)})};
  std::vector<DualQuat> dqs(2);
  ASSERT_TRUE((DualQuatPaletteJob{palette, dqs}.run()));
  std::vector<glm::vec3> pos{{1, 0, 0}, {0, 5, -2}}, lbs(2), dqsOut(2);
  std::vector<std::uint16_t> joints{0, 1, 0, 0, 1, 0, 0, 0};
  std::vector<float> weights{1, 0, 0, 0, 1, 0, 0, 0};
  ASSERT_TRUE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, dqs, lbs).run());
  ASSERT_TRUE(makeJob(SkinningMethod::DualQuat, 4, pos, joints, weights, palette, dqs, dqsOut).run());
  for (int v = 0; v < 2; ++v) EXPECT_LT(glm::distance(lbs[static_cast<std::size_t>(v)], dqsOut[static_cast<std::size_t>(v)]), 1e-5f);
}

TEST(Skinning, DualQuatKeepsVolumeWhereLinearCollapses) {
  // Two joints on the x axis, the second twisted 180 degrees about x; a vertex
  // one unit from the axis weighted half and half. LBS averages the two
  // positions to the axis (the candy-wrapper artefact); DQS rotates it 90
  // degrees and keeps its distance.
  std::vector<glm::mat4> palette{glm::mat4(1.0f), toMatrix(Srt{glm::vec3(1), glm::angleAxis(3.14159265f, glm::vec3(1, 0, 0)), glm::vec3(0)})};
  std::vector<DualQuat> dqs(2);
  ASSERT_TRUE((DualQuatPaletteJob{palette, dqs}.run()));
  std::vector<glm::vec3> pos{{0.5f, 1, 0}}, lbs(1), dq(1);
  std::vector<std::uint16_t> joints{0, 1, 0, 0};
  std::vector<float> weights{0.5f, 0.5f, 0, 0};
  ASSERT_TRUE(makeJob(SkinningMethod::Linear, 4, pos, joints, weights, palette, dqs, lbs).run());
  ASSERT_TRUE(makeJob(SkinningMethod::DualQuat, 4, pos, joints, weights, palette, dqs, dq).run());
  auto radius = [](glm::vec3 p) { return std::sqrt(p.y * p.y + p.z * p.z); };
  EXPECT_LT(radius(lbs[0]), 1e-3f);
  EXPECT_NEAR(radius(dq[0]), 1.0f, 1e-5f);
  EXPECT_NEAR(dq[0].x, 0.5f, 1e-5f);
}

TEST(Blending, NormalisesWeightsAndFallsBackToRest) {
  std::vector<Srt> a(1), b(1), rest(1), out(1);
  a[0].translation = glm::vec3(2, 0, 0);
  b[0].translation = glm::vec3(0, 2, 0);
  b[0].rotation = -glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
  rest[0].translation = glm::vec3(9);
  std::vector<BlendingJob::Layer> layers{{a, 1.0f}, {b, 3.0f}};
  ASSERT_TRUE((BlendingJob{layers, rest, out}.run()));
  EXPECT_LT(glm::distance(out[0].translation, glm::vec3(0.5f, 1.5f, 0)), 1e-6f);
  EXPECT_NEAR(glm::length(out[0].rotation), 1.0f, 1e-6f);
  std::vector<BlendingJob::Layer> zero{{a, 0.0f}, {b, 0.0f}};
  ASSERT_TRUE((BlendingJob{zero, rest, out}.run()));
  EXPECT_EQ(out[0].translation, glm::vec3(9));
  std::vector<BlendingJob::Layer> negative{{a, -1.0f}};
  EXPECT_FALSE((BlendingJob{negative, rest, out}.validate()));
}

}  // namespace
}  // namespace engine
