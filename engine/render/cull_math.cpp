#include "render/cull_math.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace engine::cull {

Counters& Counters::operator+=(const Counters& o) {
  instancesTested += o.instancesTested;
  instancesFrustum += o.instancesFrustum;
  instancesOccluded += o.instancesOccluded;
  clustersTested += o.clustersTested;
  clustersFrustum += o.clustersFrustum;
  clustersOccluded += o.clustersOccluded;
  return *this;
}

ClusterRange appendClusters(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                            std::uint32_t first, std::uint32_t count, std::vector<Cluster>& out) {
  constexpr std::uint32_t per = 3 * kClusterTriangles;
  const ClusterRange range{std::uint32_t(out.size()), (count + per - 1) / per};
  Cluster whole{glm::vec3(std::numeric_limits<float>::max()), first, glm::vec3(-std::numeric_limits<float>::max()),
                count};
  for (std::uint32_t start = 0; start < count; start += per) {
    Cluster c{glm::vec3(std::numeric_limits<float>::max()), first + start,
              glm::vec3(-std::numeric_limits<float>::max()), std::min(per, count - start)};
    for (std::uint32_t i = c.firstIndex; i < c.firstIndex + c.indexCount && i < indices.size(); ++i) {
      const std::uint32_t v = indices[i];
      if (v >= positions.size()) continue;  // the loader refuses these; never read past the end
      c.lo = glm::min(c.lo, positions[v]);
      c.hi = glm::max(c.hi, positions[v]);
    }
    whole.lo = glm::min(whole.lo, c.lo);
    whole.hi = glm::max(whole.hi, c.hi);
    out.push_back(c);
  }
  out.push_back(whole);
  return range;
}

HiZ HiZ::build(std::span<const float> depth, int width, int height) {
  HiZ hiz;
  hiz.width = width;
  hiz.height = height;
  for (int level = 1; level <= hizLevelCount(width, height); ++level) {
    const std::span<const float> source = level == 1 ? depth : std::span<const float>(hiz.levels.back());
    const int sw = hiz.levelWidth(level - 1), sh = hiz.levelHeight(level - 1);
    const int dw = hiz.levelWidth(level), dh = hiz.levelHeight(level);
    std::vector<float> next(size_t(dw) * size_t(dh));
    for (int y = 0; y < dh; ++y)
      for (int x = 0; x < dw; ++x) {
        // The last column and row take everything up to the edge (hiz.comp alike).
        const int x1 = x == dw - 1 ? sw - 1 : 2 * x + 1, y1 = y == dh - 1 ? sh - 1 : 2 * y + 1;
        float farthest = source[size_t(std::min(2 * y, sh - 1) * sw + std::min(2 * x, sw - 1))];
        for (int yy = 2 * y; yy <= y1; ++yy)
          for (int xx = 2 * x; xx <= x1; ++xx) farthest = std::min(farthest, source[size_t(yy * sw + xx)]);
        next[size_t(y * dw + x)] = farthest;
      }
    hiz.levels.push_back(std::move(next));
  }
  return hiz;
}

namespace {

// Whether every corner lies beyond one clip plane (zero-to-one depth: 0 <= z <= w).
// Linear in clip space, so it holds for every point of the box, behind the camera
// too; each comparison keeps a margin relative to the terms' size.
bool outsideFrustum(const glm::vec4 (&c)[8]) {
  bool out[6] = {true, true, true, true, true, true};
  for (const glm::vec4& p : c) {
    const float mx = kClipMargin * (std::abs(p.x) + std::abs(p.w));
    const float my = kClipMargin * (std::abs(p.y) + std::abs(p.w));
    const float mz = kClipMargin * (std::abs(p.z) + std::abs(p.w));
    out[0] = out[0] && p.x < -p.w - mx;
    out[1] = out[1] && p.x > p.w + mx;
    out[2] = out[2] && p.y < -p.w - my;
    out[3] = out[3] && p.y > p.w + my;
    out[4] = out[4] && p.z < -mz;        // beyond the far plane (reverse-Z: depth 0)
    out[5] = out[5] && p.z > p.w + mz;   // in front of the near plane
  }
  return out[0] || out[1] || out[2] || out[3] || out[4] || out[5];
}

// A window coordinate, clamped before it becomes an int (a corner near the
// camera plane projects anywhere).
int pixel(float ndc, int size, int widen) {
  const float window = std::clamp((ndc * 0.5f + 0.5f) * float(size), -4.0f, float(size) + 4.0f);
  return std::clamp(int(std::floor(window)) + widen, 0, size - 1);
}

// Whether the box, in front of the camera, is behind what the pyramid holds at
// every pixel its projection could touch: its nearest depth (the largest, reverse
// -Z; a linear-fractional function over a box peaks at a corner) against the
// farthest of the texels of the first level where its pixel rectangle, widened by
// a pixel each way, spans at most kHiZSpan texels a side.
bool hidden(const glm::vec4 (&c)[8], const HiZ& hiz, float depthMargin) {
  float nearest = 0.0f;
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec4& p : c) {
    if (!(p.w > 0.0f)) return false;  // reaches behind the camera: no rectangle to test
    const glm::vec2 ndc(p.x / p.w, p.y / p.w);
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
    nearest = std::max(nearest, p.z / p.w);
  }
  const int x0 = pixel(lo.x, hiz.width, -1), x1 = pixel(hi.x, hiz.width, 1);
  const int y0 = pixel(lo.y, hiz.height, -1), y1 = pixel(hi.y, hiz.height, 1);
  const int last = int(hiz.levels.size());
  int level = 1;
  while (level < last && ((x1 >> level) - (x0 >> level) >= kHiZSpan || (y1 >> level) - (y0 >> level) >= kHiZSpan))
    ++level;
  const int w = hiz.levelWidth(level), h = hiz.levelHeight(level);
  const int tx0 = std::min(x0 >> level, w - 1), tx1 = std::min(x1 >> level, w - 1);
  const int ty0 = std::min(y0 >> level, h - 1), ty1 = std::min(y1 >> level, h - 1);
  float farthest = hiz.at(level, tx0, ty0);
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) farthest = std::min(farthest, hiz.at(level, tx, ty));
  return nearest * (1.0f + depthMargin) < farthest;
}

}  // namespace

Verdict testBox(const View& view, const glm::mat4& model, glm::vec3 lo, glm::vec3 hi) {
  glm::vec4 corners[8];
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    corners[i] = view.viewProjection * (model * glm::vec4(p, 1.0f));  // scene.vert's order
  }
  if (outsideFrustum(corners)) return Verdict::Frustum;
  if (view.hiz && hidden(corners, *view.hiz, view.depthMargin)) return Verdict::Occluded;
  return Verdict::Visible;
}

void cullJobs(std::span<const Job> jobs, std::span<const Cluster> clusters, const View& view,
              std::span<Command> commands, Counters& counters) {
  std::vector<bool> visible;
  for (const Job& job : jobs) {
    const std::span<Command> out = commands.subspan(job.firstCommand, commandCount(job));
    std::fill(out.begin(), out.end(), Command{});
    ++counters.instancesTested;
    if (job.sphere.w >= 0.0f) {
      const glm::vec3 c(job.sphere), r(job.sphere.w);
      const Verdict v = testBox(view, glm::mat4(1.0f), c - r, c + r);
      if (v == Verdict::Frustum) ++counters.instancesFrustum;
      if (v == Verdict::Occluded) ++counters.instancesOccluded;
      if (v != Verdict::Visible) continue;
    }
    if (job.flags & kInstanceOnly) {
      const Cluster& whole = clusters[job.firstCluster + job.clusterCount];
      out[0] = {whole.indexCount, 1, whole.firstIndex, 0, 0};
      continue;
    }
    visible.assign(job.clusterCount, false);
    for (std::uint32_t i = 0; i < job.clusterCount; ++i) {
      const Cluster& c = clusters[job.firstCluster + i];
      ++counters.clustersTested;
      const Verdict v = testBox(view, job.model, c.lo, c.hi);
      if (v == Verdict::Frustum) ++counters.clustersFrustum;
      if (v == Verdict::Occluded) ++counters.clustersOccluded;
      visible[i] = v == Verdict::Visible;
    }
    // Each run of visible clusters within a chunk: one command at its first
    // cluster's slot.
    for (std::uint32_t i = 0; i < job.clusterCount; ++i) {
      const std::uint32_t end = std::min(job.clusterCount, (i / kMergeChunk + 1) * kMergeChunk);
      if (!visible[i] || (i % kMergeChunk > 0 && visible[i - 1])) continue;
      std::uint32_t count = 0, run = 0;
      for (std::uint32_t j = i; j < end && visible[j]; ++j, ++run) count += clusters[job.firstCluster + j].indexCount;
      const Cluster& head = clusters[job.firstCluster + i];
      out[i] = job.flags & kInstances ? Command{head.indexCount, run, head.firstIndex, 0, job.firstInstance + i}
                                      : Command{count, 1, head.firstIndex, 0, 0};
    }
  }
}

}  // namespace engine::cull
