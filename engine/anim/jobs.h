#pragma once
// Per-frame animation work as small job structs (after ozz-animation): the caller
// owns every buffer and passes spans; validate() checks the spans fit, run()
// validates then computes. No job allocates, so a frame costs no heap traffic.
//
// The chain for one character:
//   SamplingJob (clip, t) -> local Srt[] -> [BlendingJob] -> LocalToModelJob -> model[]
//   -> SkinningPaletteJob -> palette[] -> SkinningJob (CPU) or upload (GPU).
// Morph targets beside it (glTF: morphed first, then skinned):
//   MorphSamplingJob (clip, t) -> weights[] -> [MorphBlendingJob] -> MorphJob (CPU)
//   -> SkinningJob, or upload (GPU).
#include <cstdint>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "anim/clip.h"
#include "core/math.h"
#include "core/result.h"

namespace engine {

// Writes the clip's pose at clip-local `time` (already wrapped, see Player).
// Joints without a track keep their rest transform.
struct SamplingJob {
  static constexpr const char* kName = "SamplingJob";
  const Clip* clip = nullptr;
  double time = 0.0;
  std::span<const Srt> restPose;
  std::span<Srt> output;
  // Slerp is exact; nlerp is the shortcut whose error bench/ measures.
  QuatInterpolation rotations = QuatInterpolation::Slerp;
  // Optional: the cursors of this character's playback of `clip`; the same pose
  // with or without.
  SamplingContext* context = nullptr;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Weighted blend of whole poses: lerp for translation and scale, nlerp for
// rotation (order independent, which slerp is not). Weights need not sum to 1;
// they are normalised. When all weights are ~0 the rest pose is written.
struct BlendingJob {
  static constexpr const char* kName = "BlendingJob";
  struct Layer {
    std::span<const Srt> pose;
    float weight = 0.0f;
  };
  std::span<const Layer> layers;
  std::span<const Srt> restPose;
  std::span<Srt> output;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Writes the clip's morph weights at clip-local `time` into `output`, a flat
// array laid out by the model's MorphLayout. Nodes without a track keep their
// rest weights.
struct MorphSamplingJob {
  static constexpr const char* kName = "MorphSamplingJob";
  const Clip* clip = nullptr;
  double time = 0.0;
  std::span<const float> restWeights;
  std::span<float> output;
  SamplingContext* context = nullptr;  // optional, as SamplingJob's

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Weighted blend of whole morph weight arrays (a cross-fade), normalised as
// BlendingJob's layers; all layer weights ~0 writes the rest weights.
struct MorphBlendingJob {
  static constexpr const char* kName = "MorphBlendingJob";
  struct Layer {
    std::span<const float> weights;
    float weight = 0.0f;
  };
  std::span<const Layer> layers;
  std::span<const float> restWeights;
  std::span<float> output;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// model[i] = root * ... * local[parent] * local[i]; needs parents[i] < i.
struct LocalToModelJob {
  static constexpr const char* kName = "LocalToModelJob";
  std::span<const int> parents;
  std::span<const Srt> locals;
  glm::mat4 root{1.0f};
  std::span<glm::mat4> models;
  // Optional: the model matrices of the first fixed.size() joints, copied rather
  // than computed (a model's static ancestors: AnimatedModel::staticModels). The
  // caller vouches that they are what the job would compute from `locals` and `root`.
  std::span<const glm::mat4> fixed{};

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// palette[k] = models[joints[k]] * inverseBinds[k]: takes a vertex from bind
// space to where its joint has moved it.
struct SkinningPaletteJob {
  static constexpr const char* kName = "SkinningPaletteJob";
  std::span<const glm::mat4> models;
  std::span<const int> joints;
  std::span<const glm::mat4> inverseBinds;
  std::span<glm::mat4> palette;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Converts a palette to dual quaternions for DQS. Scale in the palette is lost.
struct DualQuatPaletteJob {
  static constexpr const char* kName = "DualQuatPaletteJob";
  std::span<const glm::mat4> palette;
  std::span<DualQuat> output;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

enum class SkinningMethod { Linear, DualQuat };

// CPU skinning of positions (and optionally normals) with `influences` joints per
// vertex (1..8; glTF gives 4 or 8). The outputs may be the inputs (in place: each
// vertex is read before it is written). Linear blends matrices (LBS); DualQuat blends
// dual quaternions (DQS), which keeps volume at twisting joints. Influences with
// zero weight or a joint past the palette are skipped, so padding entries of
// JOINTS_n never read outside the palette.
struct SkinningJob {
  static constexpr const char* kName = "SkinningJob";
  SkinningMethod method = SkinningMethod::Linear;
  int influences = 4;
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;  // optional
  std::span<const std::uint16_t> joints;  // influences per vertex
  std::span<const float> weights;         // influences per vertex
  std::span<const glm::mat4> palette;     // for Linear
  std::span<const DualQuat> dualQuats;    // for DualQuat
  std::span<glm::vec3> outPositions;
  std::span<glm::vec3> outNormals;  // needed when normals are given

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Morph targets on the CPU: out = base + sum_t weights[t] * delta_t for positions,
// normals and tangents (xyz; the handedness w is kept), in target order as the
// shader adds them. Deltas are target-major (PrimitiveData): target t moves vertex
// v by deltas[t * vertices + v]; an empty delta span copies that attribute. Zero
// weights are skipped. Each output may be its input (in place). Normals are not
// renormalised: skinning and shading do that.
struct MorphJob {
  static constexpr const char* kName = "MorphJob";
  std::span<const float> weights;  // one per target
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> positionDeltas;
  std::span<glm::vec3> outPositions;
  std::span<const glm::vec3> normals;  // optional, as the two below
  std::span<const glm::vec3> normalDeltas;
  std::span<glm::vec3> outNormals;
  std::span<const glm::vec4> tangents;  // optional, as the two below
  std::span<const glm::vec3> tangentDeltas;
  std::span<glm::vec4> outTangents;

  bool validate() const;
  [[nodiscard]] bool run() const;
};

// Runs `job`; a job that rejects its inputs (spans of the wrong size, a missing
// clip) is a bug in the caller, reported as an error naming `where` and the job.
template <typename Job>
Status runJob(const Job& job, const std::string& where) {
  if (job.run()) return Ok{};
  return makeError(where + ": " + Job::kName + " rejected its inputs");
}

}  // namespace engine
