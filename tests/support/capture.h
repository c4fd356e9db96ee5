#pragma once
// Runs a model shader variant over every vertex of a primitive with transform
// feedback (rasterisation discarded) and reads back one varying per vertex: how
// the GL tests compare GPU skinning and morphing with the CPU jobs. Also the CPU
// pose (joints, weights, palettes) both sides are given.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "anim/jobs.h"
#include "anim/model_builder.h"
#include "core/math.h"
#include "gl/bindings.h"
#include "gl/resources.h"
#include "render/frame_block.h"
#include "render/model_renderer.h"
#include "render/render_target.h"

namespace engine::test {

// One pose of a model: joint matrices (per runtime joint) and every morphing
// node's weights (MorphLayout order).
struct ModelPose {
  std::vector<glm::mat4> models;
  std::vector<float> weights;
};

inline ModelPose poseModel(const AnimatedModel& animated, int clip, double time) {
  const Skeleton& skeleton = animated.skeleton;
  ModelPose pose;
  std::vector<Srt> locals(skeleton.restPose().begin(), skeleton.restPose().end());
  pose.weights = animated.morphs.restWeights;
  if (clip >= 0) {
    const Clip& c = animated.clips[size_t(clip)];
    EXPECT_TRUE((SamplingJob{&c, time, skeleton.restPose(), locals}.run()));
    EXPECT_TRUE((MorphSamplingJob{&c, time, animated.morphs.restWeights, pose.weights}.run()));
  }
  pose.models.resize(locals.size());
  EXPECT_TRUE((LocalToModelJob{skeleton.parents(), locals, glm::mat4(1.0f), pose.models}.run()));
  return pose;
}

struct Palettes {
  std::vector<glm::mat4> palette;
  std::vector<DualQuat> dualQuats;
};

inline Palettes palettesOf(const Skin& skin, const ModelPose& pose) {
  Palettes p;
  p.palette.resize(skin.joints.size());
  p.dualQuats.resize(skin.joints.size());
  EXPECT_TRUE((SkinningPaletteJob{pose.models, skin.joints, skin.inverseBinds, p.palette}.run()));
  EXPECT_TRUE((DualQuatPaletteJob{p.palette, p.dualQuats}.run()));
  return p;
}

// The frame block (common/frame.glsl) that every scene program reads, uploaded and
// bound at its binding; keep the buffer while drawing.
inline gl::Buffer bindFrameBlock(const FrameBlock& block = {}) {
  gl::Buffer buffer = gl::Buffer::fromSpan(std::span<const FrameBlock>(&block, 1));
  glBindBufferBase(GL_UNIFORM_BUFFER, gl::binding::kFrameBlock, buffer.id());
  return buffer;
}

// What a capture draws with besides the primitive.
struct CaptureInputs {
  std::span<const glm::mat4> palette;   // skinned LBS variants
  std::span<const DualQuat> dualQuats;  // skinned DQS variants
  std::span<const float> morphWeights;  // MORPH variants: the drawn node's weights
  glm::mat4 model{1.0f};                // u_model (its inverse transpose is u_normalMatrix)
};

// Values read back one per vertex of `prim`'s buffers as one per vertex of its
// PrimitiveData (a vertex the indices never use keeps T{}): a triangle list's
// buffers hold its runs' copies of the vertices (render/model_renderer.h), and
// every copy of a vertex must have come out the same, bit for bit.
template <typename T>
std::vector<T> perSourceVertex(const GpuPrimitive& prim, const std::vector<T>& values) {
  if (prim.sourceVertex.empty()) return values;
  std::vector<T> out(*std::max_element(prim.sourceVertex.begin(), prim.sourceVertex.end()) + 1u);
  std::vector<char> seen(out.size(), 0);
  for (std::size_t i = 0; i < values.size() && i < prim.sourceVertex.size(); ++i) {
    const std::uint32_t v = prim.sourceVertex[i];
    if (seen[v]) {
      EXPECT_EQ(std::memcmp(&out[v], &values[i], sizeof(T)), 0) << "copy " << i << " of vertex " << v;
      continue;
    }
    out[v] = values[i];
    seen[v] = 1;
  }
  return out;
}

// Runs `variant` of the scene programs (scene.vert) over every vertex of `prim` and
// returns the captured `varying` (one T per PrimitiveData vertex, in order:
// perSourceVertex). The frame block's view-projection is the identity.
template <typename T>
std::vector<T> captureVarying(ShaderVariants& variants, const GpuPrimitive& prim, const CaptureInputs& inputs,
                              const ShaderVariant& variant, const std::string& varying) {
  auto program = variants.get(variant, {varying});
  EXPECT_TRUE(program.ok()) << program.error().message;
  if (!program) return {};
  const gl::Program& p = **program;
  p.use();
  p.set("u_model", inputs.model);
  p.set("u_normalMatrix", glm::mat3(glm::transpose(glm::inverse(glm::mat3(inputs.model)))));
  const gl::Buffer frame = bindFrameBlock();
  gl::Buffer skin;
  gl::Texture palette;
  if (variant.influences > 0) {
    std::vector<glm::vec4> rows;
    lbsPaletteRows(inputs.palette, rows);
    skin = variant.mode == SkinMode::DualQuat ? gl::Buffer::fromSpan(inputs.dualQuats)
                                              : gl::Buffer::fromSpan(std::span<const glm::vec4>(rows));
    palette = gl::Texture::ofBuffer(skin, GL_RGBA32F);
    palette.bind(gl::binding::kSkinPalette);
  }
  gl::Buffer weights;
  if (variant.morph) {
    // At least one float: a storage buffer may not be empty.
    std::vector<float> w(inputs.morphWeights.begin(), inputs.morphWeights.end());
    w.resize(std::max<size_t>(1, w.size()));
    weights = gl::Buffer::fromSpan(std::span<const float>(w));
    bindMorphTargets(p, prim, weights, 0);
  }
  const gl::Buffer captured = gl::Buffer::create(size_t(prim.vertexCount) * sizeof(T));
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.id());
  // EGL surfaceless has no default framebuffer; draws need one bound even when
  // rasterisation is discarded.
  auto target = RenderTarget::create(1, 1, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  glEnable(GL_RASTERIZER_DISCARD);
  prim.vao.bind();
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, prim.vertexCount);  // one output per vertex, in order
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<T> out(size_t(prim.vertexCount));
  glGetNamedBufferSubData(captured.id(), 0, GLsizeiptr(out.size() * sizeof(T)), out.data());
  return perSourceVertex(prim, out);
}

// The diagonal of the points' bounding box.
inline double sizeOf(const std::vector<glm::vec3>& points) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

// Largest |a - b| over the points, relative to the size of `b`.
inline double largestRelativeError(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, double(glm::length(a[i] - b[i])));
  return worst / std::max(1e-12, sizeOf(b));
}

}  // namespace engine::test
