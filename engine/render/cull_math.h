#pragma once
// GPU culling's data and its CPU twin (issue 16: "GPU culling"). GL-free: the
// compute shaders (shaders/cull/hiz.comp, shaders/cull/cull.comp) run the same
// math on the GPU, and tests/render/gpu_cull_test.cpp checks them against this.
//
// What it guarantees: a culled cluster or instance is one none of whose fragments
// could pass the main view's depth test (GL_GREATER, reverse-Z), so culling
// changes no pixel. Clusters are consecutive runs of a mesh's own index buffer
// and the commands keep their order, so even depth ties resolve as before.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace engine::cull {

// At most this many triangles a cluster (the 128): small enough that a
// partly hidden mesh loses its hidden parts, large enough that a visible mesh's
// draw is not split into many (the shader merges visible neighbours again).
inline constexpr std::uint32_t kClusterTriangles = 128;

// cull.comp merges visible neighbours within chunks of this many clusters (its
// shared memory); the CPU twin does the same.
inline constexpr std::uint32_t kMergeChunk = 1024;

// A run of a mesh's indices and the bounds of the vertices it uses, mesh space.
// std430 layout of cull.comp's Cluster: vec3 + uint, vec3 + uint.
struct Cluster {
  glm::vec3 lo{0.0f};
  std::uint32_t firstIndex = 0;
  glm::vec3 hi{0.0f};
  std::uint32_t indexCount = 0;
};
static_assert(sizeof(Cluster) == 32);

// Clusters [first, first + count) of one index range, then one more at first +
// count covering the whole range (a deforming mesh's: its vertices move, so only
// its instance's bounds are tested, and it is drawn in one command).
struct ClusterRange {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// Splits triangle indices [first, first + count) into runs of at most
// kClusterTriangles triangles, each bounded by the positions it references, and
// appends them to `out` followed by the whole range's entry; `base` is added to
// the returned range's first (the index of out[0] in a larger table).
ClusterRange appendClusters(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                            std::uint32_t first, std::uint32_t count, std::vector<Cluster>& out);

// One instance of one mesh to cull and draw: cull.comp's Job (std430).
struct Job {
  glm::mat4 model{1.0f};   // mesh -> camera-relative world: the draw's own u_model
  glm::vec4 sphere{0.0f};  // the instance's bounds, camera-relative; w < 0: none
  std::uint32_t firstCluster = 0;
  std::uint32_t clusterCount = 0;  // its whole-range entry follows them
  std::uint32_t firstCommand = 0;
  std::uint32_t flags = 0;
  std::uint32_t firstInstance = 0;  // kInstances: the instance of its first cluster
  std::uint32_t pad[3] = {0, 0, 0};
};
static_assert(sizeof(Job) == 112);
// The mesh deforms (skinned, morphed): its clusters' bounds do not hold, so the
// instance's sphere alone is tested and one command draws the whole range.
inline constexpr std::uint32_t kInstanceOnly = 1;
// The clusters are instances of one mesh (the terrain's patches: each the same
// grid, its own box): a run of visible ones is one instanced command, of the
// first's indices, as many instances as the run, from firstInstance + its index.
inline constexpr std::uint32_t kInstances = 2;

// glMultiDrawElementsIndirect's command.
struct Command {
  std::uint32_t count = 0;
  std::uint32_t instanceCount = 0;
  std::uint32_t firstIndex = 0;
  std::int32_t baseVertex = 0;
  std::uint32_t baseInstance = 0;
};
static_assert(sizeof(Command) == 20);

// How many commands a job writes: one per cluster, or one for the whole range.
inline std::uint32_t commandCount(const Job& job) { return job.flags & kInstanceOnly ? 1u : job.clusterCount; }

// What --bench reports, summed over a frame's dispatches (cull.comp's atomics).
struct Counters {
  std::uint32_t instancesTested = 0, instancesFrustum = 0, instancesOccluded = 0;
  std::uint32_t clustersTested = 0, clustersFrustum = 0, clustersOccluded = 0;
  std::uint32_t pad[2] = {0, 0};
  Counters& operator+=(const Counters& o);
};
static_assert(sizeof(Counters) == 32);

// A hierarchical-Z pyramid of a reverse-Z depth buffer of width x height pixels:
// level k (GL's mip sizes, max(1, size >> k)) holds the least (farthest) depth of
// the texels of level k - 1 below it; a last row or column of odd length folds
// into its neighbour, so every texel of level k covers at least pixels [x << k,
// (x + 1) << k) and the last texels the rest: no pixel is left out of any level.
// Level 0, the depth itself, is not kept: copying it cost llvmpipe as much as
// reducing it (10 ms at 1280x720), and a test never needs it (a box spanning
// at most two pixels a side is rare and cheap to draw).
struct HiZ {
  int width = 0, height = 0;
  std::vector<std::vector<float>> levels;  // levels[k - 1] is level k; row-major, bottom row first (GL's)
  static HiZ build(std::span<const float> depth, int width, int height);
  int levelWidth(int level) const { return std::max(1, width >> level); }
  int levelHeight(int level) const { return std::max(1, height >> level); }
  float at(int level, int x, int y) const { return levels[size_t(level - 1)][size_t(y * levelWidth(level) + x)]; }
};
// The levels kept, 1 to this (at least one: the 1 x 1 top).
inline int hizLevelCount(int width, int height) {
  int levels = 1;
  while ((std::max(width, height) >> (levels + 1)) > 0) ++levels;
  return levels;
}

// Margins, relative: the draw's vertex shader computes u_viewProjection * (u_model
// * p) in float as cull.comp does, but the rasteriser interpolates depth its own
// way and the corners of a box are not the vertices. A relative 1e-4 of depth is
// 1 cm at 100 m; of clip space, 0.01 % of the view's width.
inline constexpr float kClipMargin = 1e-4f;
inline constexpr float kDepthMargin = 1e-4f;

// A box's pixel rectangle is tested on the finest level where it spans at most
// this many texels a side (up to 64 reads). 2 x 2, the textbook choice, reads a
// footprint up to twice the rectangle each way: a character behind a wall kept
// seeing the sky above it (50 CesiumMan behind a wall: none culled at 2, the
// hidden rows at 8).
inline constexpr int kHiZSpan = 8;

enum class Verdict : std::uint32_t { Visible = 0, Frustum = 1, Occluded = 2 };

// The view a dispatch culls for.
struct View {
  glm::mat4 viewProjection{1.0f};  // camera-relative world -> clip (zero-to-one depth, reverse-Z)
  const HiZ* hiz = nullptr;        // null: frustum culling only
  // Tests only: a negative margin culls what is a little in front of the depth
  // (non-conservative on purpose), which the image comparisons must catch.
  float depthMargin = kDepthMargin;
};

// A mesh-space box through `model` and the view: outside the frustum (every
// corner beyond one clip plane), hidden (every pixel it could cover has a nearer
// depth in the view's pyramid; none: frustum only), or possibly visible.
Verdict testBox(const View& view, const glm::mat4& model, glm::vec3 lo, glm::vec3 hi);

// cull.comp on the CPU: writes every command of `jobs` into `commands` (sized by
// the caller to cover every job's firstCommand + commandCount) and adds to
// `counters`. A culled instance's commands are all empty; a visible one's clusters
// are tested each, and each run of visible clusters becomes one command at its
// first cluster's slot (the others empty): a mesh with nothing culled is drawn
// by exactly the one command its plain draw was.
void cullJobs(std::span<const Job> jobs, std::span<const Cluster> clusters, const View& view,
              std::span<Command> commands, Counters& counters);

}  // namespace engine::cull
