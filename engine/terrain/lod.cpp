#include "terrain/lod.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>
#include <utility>

namespace engine::terrain {
namespace {

// Root-level morph distances far beyond any distance: its k is always 0.
constexpr float kNoMorphStart = 1e30f;
constexpr float kNoMorphEnd = 2e30f;
// Relative slack that keeps conditions (b) and (c) true through float rounding.
constexpr double kRangeSlack = 1.001;
// Blocks count toward a level's range (and are measured) out to this multiple of
// the distance where the level-wide error estimate projects to the target: for
// noise the estimate comes from probes, and has been seen 1.3x under the exact
// maximum (level 1 of micro_bench's 4 km field).
constexpr double kPruneSafety = 2.0;

glm::dvec4 row(const glm::mat4& m, int r) { return {m[0][r], m[1][r], m[2][r], m[3][r]}; }

// Pixels per metre of error at distance 1.
double pixelsPerMetre(const LodCamera& camera) {
  return camera.viewportHeight / (2.0 * std::tan(camera.fovY * 0.5));
}

struct Selector {
  const Terrain& terrain;
  const LodCamera& camera;
  LodSelection& out;
  Frustum frustum;
  glm::dvec2 cameraSample;  // camera (x, z) in sample units from the origin
  double dy2 = 0.0;         // squared vertical distance used by every distance

  // Distance (metres) from the camera to the nearest point of a rectangle of
  // samples, in the metric of the header comment.
  double distance(int x0, int z0, int x1, int z1) const {
    const double dx = std::max({double(x0) - cameraSample.x, 0.0, cameraSample.x - double(x1)});
    const double dz = std::max({double(z0) - cameraSample.y, 0.0, cameraSample.y - double(z1)});
    const double s = terrain.spacing();
    return std::sqrt((dx * dx + dz * dz) * s * s + dy2);
  }
  double farthest(int x0, int z0, int x1, int z1) const {
    const double dx = std::max(std::abs(x0 - cameraSample.x), std::abs(x1 - cameraSample.x));
    const double dz = std::max(std::abs(z0 - cameraSample.y), std::abs(z1 - cameraSample.y));
    const double s = terrain.spacing();
    return std::sqrt((dx * dx + dz * dz) * s * s + dy2);
  }

  bool visible(int level, int x0, int z0, int span) const {
    if (!camera.cull) return true;
    const HeightRange h = terrain.regionBounds(x0, z0, x0 + span, z0 + span);
    const double s = terrain.spacing();
    const glm::dvec3 o = terrain.origin() - camera.position;
    const int x1 = std::min(x0 + span, terrain.cellsX()), z1 = std::min(z0 + span, terrain.cellsZ());
    (void)level;
    return frustum.intersects({o.x + x0 * s, o.y + h.min, o.z + z0 * s},
                              {o.x + x1 * s, o.y + h.max, o.z + z1 * s});
  }

  void addPatch(int level, const PageKey& node, int qx, int qz) {
    const int s = Terrain::stride(level);
    const int span = kPatchQuads * s;
    const int gx = node.nx * kNodeQuads * s + qx * span, gz = node.nz * kNodeQuads * s + qz * span;
    if (gx >= terrain.cellsX() || gz >= terrain.cellsZ()) return;  // wholly outside the field
    if (!visible(level, gx, gz, span)) return;
    LodPatch p{level, gx, gz, node, 0.0f};
    const PageKey area = patchArea(p);
    p.error = terrain.meshError(level, area);
    const int top = terrain.levelCount() - 1;
    if (level < top && farthest(gx, gz, gx + span, gz + span) > out.morphStart[std::size_t(level)])
      p.error = std::max(p.error, terrain.meshError(level + 1, area));
    out.patches.push_back(p);
  }

  void addNode(const PageKey& node) {
    for (int q = 0; q < 4; ++q) addPatch(node.level, node, q & 1, q >> 1);
  }

  // Strugar's LODSelect: false when the node is beyond its level's range, so the
  // parent must draw that area itself.
  bool select(const PageKey& node) {
    const int span = kNodeQuads * Terrain::stride(node.level);
    const int x0 = node.nx * span, z0 = node.nz * span;
    if (x0 >= terrain.cellsX() || z0 >= terrain.cellsZ()) return true;
    const int x1 = std::min(x0 + span, terrain.cellsX()), z1 = std::min(z0 + span, terrain.cellsZ());
    const double d = distance(x0, z0, x1, z1);
    if (d > out.range[std::size_t(node.level)]) return false;
    if (!visible(node.level, x0, z0, span)) return true;
    if (node.level == 0 || d > out.range[std::size_t(node.level - 1)]) {
      addNode(node);
      return true;
    }
    for (int q = 0; q < 4; ++q) {
      const PageKey child{node.level - 1, node.nx * 2 + (q & 1), node.nz * 2 + (q >> 1)};
      if (!select(child)) addPatch(node.level, node, q & 1, q >> 1);
    }
    return true;
  }

  // How far blocks can matter to level `level`'s range: beyond, they are taken to be
  // fine without being measured.
  double reach(int level, double metresPerPixel) const {
    return kPruneSafety * terrain.geometricError(level) / metresPerPixel;
  }

  // Measures up to `budget` of the unmeasured blocks within reach of the finest
  // measured level, nearest first; returns how many are left (with a budget of 0,
  // counts them).
  std::size_t measureNearest(double metresPerPixel, std::size_t budget) const {
    const int level = std::min(kExactErrorLevels, terrain.levelCount() - 1);
    if (level < 1) return 0;
    std::vector<std::pair<double, PageKey>> unmeasured;
    forBlocksWithin(root(), reach(level, metresPerPixel), [&](const PageKey& n, double d, double) {
      if (!terrain.errorsMeasured(n)) unmeasured.emplace_back(d, n);
    });
    const std::size_t now = std::min(unmeasured.size(), budget);
    std::partial_sort(unmeasured.begin(), unmeasured.begin() + std::ptrdiff_t(now), unmeasured.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < now; ++i) terrain.measureErrors(unmeasured[i].second);
    return unmeasured.size() - now;
  }

  PageKey root() const { return {terrain.levelCount() - 1, 0, 0}; }

  // The distance beyond which the level-`level` mesh's error projects under target
  // (`metresPerPixel`: metres of error a pixel at distance 1) in every block
  // (level-1 node) that it would cover: a block needs the mesh kept beyond
  // the distance r of its own error, unless it lies wholly beyond r already, or
  // wholly within it (then finer levels cover it).
  double neededStart(int level, double metresPerPixel) const {
    double needed = 0.0;
    forBlocksWithin(root(), reach(level, metresPerPixel), [&](const PageKey& n, double d, double far) {
      const double r = terrain.meshError(level, n) / metresPerPixel;
      if (d < r) needed = std::max(needed, std::min(r, far));
    });
    return needed;
  }

  // Calls f(block, nearest, farthest) for each block (level-1 node) under `node`
  // nearer than `reach`, in view or not: ranges that hung on the view's direction
  // would change the mesh as the camera turns, and give the sun's maps, culled to
  // another box, other ranges than the view whose surface they shadow.
  template <typename F>
  void forBlocksWithin(const PageKey& node, double reach, F&& f) const {
    const int span = kNodeQuads * Terrain::stride(node.level);
    const int x0 = node.nx * span, z0 = node.nz * span;
    if (x0 >= terrain.cellsX() || z0 >= terrain.cellsZ()) return;
    const int x1 = std::min(x0 + span, terrain.cellsX()), z1 = std::min(z0 + span, terrain.cellsZ());
    const double d = distance(x0, z0, x1, z1);
    if (d >= reach || node.level < 1) return;  // (a one-node field has no blocks)
    if (node.level == 1) return f(node, d, farthest(x0, z0, x1, z1));
    for (int q = 0; q < 4; ++q)
      forBlocksWithin(PageKey{node.level - 1, node.nx * 2 + (q & 1), node.nz * 2 + (q >> 1)}, reach, f);
  }
};

// Where morphing toward `level` must start: from the blocks' errors near the
// camera where the terrain measures them, else where the level-wide error
// projects to the target.
double morphStartFor(const Selector& selector, int level, double metresPerPixel) {
  if (level <= kExactErrorLevels) return selector.neededStart(level, metresPerPixel);
  return selector.terrain.geometricError(level) / metresPerPixel;
}

void computeRanges(const Selector& selector, double errorPixels, LodSelection& out) {
  const Terrain& terrain = selector.terrain;
  const int top = terrain.levelCount() - 1;
  const double k = pixelsPerMetre(selector.camera);
  const double target = std::max(errorPixels, 1e-6);
  out.stats.blocksPending = selector.measureNearest(target / k, 0);
  for (int level = 0; level < top; ++level) {
    // Morphing toward level + 1 starts where that level's error projects to the target
    // (at least a sample away: the morph needs a range of positive length).
    const double acceptable = std::max(morphStartFor(selector, level + 1, target / k), terrain.spacing());
    double range = acceptable / kMorphStartRatio;
    if (level > 0) {
      // (a) and (c): a level-(L-1) node reaches at most its range plus its diagonal;
      // there level L must not have begun morphing.
      const double prev = out.range[std::size_t(level - 1)];
      range = std::max(range, (prev + std::sqrt(2.0) * terrain.nodeSize(level - 1)) / kMorphStartRatio * kRangeSlack);
    }
    out.range[std::size_t(level)] = range;
    out.morphStart[std::size_t(level)] = float(range * kMorphStartRatio);
    out.morphEnd[std::size_t(level)] = float(range * kMorphEndRatio);
  }
  out.range[std::size_t(top)] = std::numeric_limits<double>::infinity();
  out.morphStart[std::size_t(top)] = kNoMorphStart;
  out.morphEnd[std::size_t(top)] = kNoMorphEnd;
}

}  // namespace

Frustum Frustum::fromViewProjection(const glm::mat4& m, bool zeroToOneDepth) {
  // Gribb and Hartmann: the clip-space inequalities -w <= x, y <= w and -w <= z <= w
  // (or 0 <= z <= w) written as planes in the space the matrix takes points from.
  // Read as -w <= z, a reverse-Z matrix would cull nothing beyond its far plane.
  Frustum f;
  const glm::dvec4 r0 = row(m, 0), r1 = row(m, 1), r2 = row(m, 2), r3 = row(m, 3);
  f.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, zeroToOneDepth ? r2 : r3 + r2, r3 - r2};
  return f;
}

bool Frustum::intersects(const glm::dvec3& lo, const glm::dvec3& hi) const {
  for (const glm::dvec4& p : planes) {
    // The box corner farthest along the plane normal.
    const glm::dvec3 c(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
    if (p.x * c.x + p.y * c.y + p.z * c.z + p.w < 0.0) return false;
  }
  return true;
}

namespace {

// The camera's place in the field, as the selection and the shaders read it; the
// camera's (x, z) in samples from the origin.
glm::dvec2 placeCamera(const Terrain& terrain, const LodCamera& camera, LodSelection& out) {
  const double s = terrain.spacing();
  // Clamped so that the integer cell and the float fraction stay meaningful for a
  // camera absurdly far away; such a camera sees only the root anyway.
  constexpr double kFar = 1 << 29;
  const glm::dvec2 cam = glm::clamp(
      glm::dvec2(camera.position.x - terrain.origin().x, camera.position.z - terrain.origin().z) / s,
      glm::dvec2(-kFar), glm::dvec2(kFar));
  const glm::dvec2 cell = glm::floor(cam);
  out.cameraCell = glm::ivec2(cell);
  out.cameraFraction = glm::vec2(cam - cell);
  const double cy = camera.position.y - terrain.origin().y;
  out.cameraHeight = float(cy);
  const HeightRange h = terrain.heightRange();
  const double dy = std::max({double(h.min) - cy, 0.0, cy - double(h.max)});
  out.morphDy2 = float(dy * dy);
  out.spacing = float(s);
  out.cells = {terrain.cellsX(), terrain.cellsZ()};
  return cam;
}

Selector makeSelector(const Terrain& terrain, const LodCamera& camera, LodSelection& out) {
  const glm::dvec2 cam = placeCamera(terrain, camera, out);
  // The selection uses the same squared height as the vertices.
  return Selector{terrain, camera, out, Frustum::fromViewProjection(camera.viewProjection, camera.zeroToOneDepth),
                  cam, double(out.morphDy2)};
}

}  // namespace

std::size_t measureBlocks(const Terrain& terrain, const LodCamera& camera, double errorPixels, std::size_t budget) {
  LodSelection placed;
  const Selector selector = makeSelector(terrain, camera, placed);
  return selector.measureNearest(std::max(errorPixels, 1e-6) / pixelsPerMetre(camera), budget);
}

LodSelection selectLod(const Terrain& terrain, const LodCamera& camera, double errorPixels) {
  LodSelection out;
  Selector selector = makeSelector(terrain, camera, out);
  computeRanges(selector, errorPixels, out);
  if (!selector.select(selector.root())) selector.addNode(selector.root());

  out.stats.patches = out.patches.size();
  out.stats.triangles = out.patches.size() * kPatchQuads * kPatchQuads * 2;
  out.stats.finestLevel = terrain.levelCount() - 1;
  out.stats.targetPixels = errorPixels;
  for (const LodPatch& p : out.patches) {
    out.stats.maxGeometricError = std::max(out.stats.maxGeometricError, p.error);
    out.stats.finestLevel = std::min(out.stats.finestLevel, p.level);
  }
  std::unordered_set<PageKey, PageKeyHash> nodes;
  for (const LodPatch& p : out.patches) nodes.insert(p.node);
  out.stats.pages = nodes.size();
  return out;
}

// 1.25^64: a target a million times the asked one; ranges are at their floor long before.
constexpr int kMaxCoarsenings = 64;

LodSelection selectLodWithin(const Terrain& terrain, const LodCamera& camera, double errorPixels,
                             std::size_t maxPages) {
  LodSelection s = selectLod(terrain, camera, errorPixels);
  int coarsenings = 0;
  double target = errorPixels;
  while (s.stats.pages > maxPages) {
    target *= kCoarsenStep;
    LodSelection coarser = selectLod(terrain, camera, target);
    ++coarsenings;
    // Ranges have a floor (each level's at least its nodes' reach), so past some
    // target nothing changes: stop there rather than loop forever.
    const bool shrank = coarser.stats.pages < s.stats.pages;
    s = std::move(coarser);
    if ((!shrank && coarsenings > 8) || coarsenings >= kMaxCoarsenings) break;
  }
  s.stats.coarsenings = coarsenings;
  return s;
}

PageKey patchArea(const LodPatch& patch) {
  if (patch.level == 0) return patch.node;
  const int span = kNodeQuads * Terrain::stride(patch.level - 1);
  return {patch.level - 1, patch.gx / span, patch.gz / span};
}

float morphFactor(const LodSelection& sel, int level, int gx, int gz) {
  const int cx = std::min(gx, sel.cells.x), cz = std::min(gz, sel.cells.y);
  const float x = (float(cx - sel.cameraCell.x) - sel.cameraFraction.x) * sel.spacing;
  const float z = (float(cz - sel.cameraCell.y) - sel.cameraFraction.y) * sel.spacing;
  const float d = std::sqrt(x * x + z * z + sel.morphDy2);
  const float start = sel.morphStart[std::size_t(level)], end = sel.morphEnd[std::size_t(level)];
  return std::clamp((d - start) / (end - start), 0.0f, 1.0f);
}

glm::vec3 patchVertex(const LodSelection& sel, const LodPatch& patch, const HeightPage& page,
                      int i, int j) {
  const int s = Terrain::stride(patch.level);
  const int gx = patch.gx + i * s, gz = patch.gz + j * s;
  const float k = morphFactor(sel, patch.level, gx, gz);
  // Odd vertices slide onto their even neighbour toward the node's origin: at k = 1
  // the grid is exactly the parent level's.
  const int oddX = i & 1, oddZ = j & 1;
  const int qx = std::min(gx - oddX * s, sel.cells.x), qz = std::min(gz - oddZ * s, sel.cells.y);
  const int px = std::min(gx, sel.cells.x), pz = std::min(gz, sel.cells.y);
  const float rx = float(px - sel.cameraCell.x) - sel.cameraFraction.x;
  const float rz = float(pz - sel.cameraCell.y) - sel.cameraFraction.y;
  const float qrx = float(qx - sel.cameraCell.x) - sel.cameraFraction.x;
  const float qrz = float(qz - sel.cameraCell.y) - sel.cameraFraction.y;
  // Position of the patch inside its node's page, in the level's samples.
  const glm::ivec2 origin = patchPageOrigin(patch);
  const int li = origin.x + i, lj = origin.y + j;
  const float hp = page.at(li, lj), hq = page.at(li - oddX, lj - oddZ);
  const float w = 1.0f - k;
  const float x = (rx * w + qrx * k) * sel.spacing;
  const float z = (rz * w + qrz * k) * sel.spacing;
  const float y = (hp * w + hq * k) - sel.cameraHeight;
  return {x, y, z};
}

namespace {

// terrain.vert's pageNormal: central differences over the page's samples `step`
// metres apart (the page's border supplies the neighbours at its edges).
glm::vec3 pageNormal(const HeightPage& page, int li, int lj, float step) {
  const float l = page.at(li - 1, lj), r = page.at(li + 1, lj);
  const float d = page.at(li, lj - 1), u = page.at(li, lj + 1);
  return glm::normalize(glm::vec3(l - r, 2.0f * step, d - u));
}

}  // namespace

glm::vec3 patchNormal(const LodSelection& sel, const LodPatch& patch, const HeightPage& page, int i, int j) {
  const int s = Terrain::stride(patch.level);
  const float k = morphFactor(sel, patch.level, patch.gx + i * s, patch.gz + j * s);
  const int oddX = i & 1, oddZ = j & 1;
  const glm::ivec2 origin = patchPageOrigin(patch);
  const int li = origin.x + i, lj = origin.y + j;
  const float step = float(s) * sel.spacing;
  const float w = 1.0f - k;
  return glm::normalize(pageNormal(page, li, lj, step) * w + pageNormal(page, li - oddX, lj - oddZ, step) * k);
}

namespace {

// `perVertex(selection, patch, page, i, j)` at every grid vertex of a patch, in the
// order patchIndices() refers to them.
template <typename PerVertex>
std::vector<glm::vec3> overPatchGrid(const Terrain& terrain, const LodSelection& selection, const LodPatch& patch,
                                     PerVertex perVertex) {
  auto page = terrain.page(patch.node);
  std::vector<glm::vec3> out;
  out.reserve(std::size_t(kPatchQuads + 1) * (kPatchQuads + 1));
  for (int j = 0; j <= kPatchQuads; ++j)
    for (int i = 0; i <= kPatchQuads; ++i) out.push_back(perVertex(selection, patch, *page, i, j));
  return out;
}

}  // namespace

std::vector<glm::vec3> patchNormals(const Terrain& terrain, const LodSelection& selection, const LodPatch& patch) {
  return overPatchGrid(terrain, selection, patch, patchNormal);
}

std::vector<glm::vec3> patchVertices(const Terrain& terrain, const LodSelection& selection,
                                     const LodPatch& patch) {
  return overPatchGrid(terrain, selection, patch, patchVertex);
}

std::vector<std::uint32_t> patchIndices() {
  std::vector<std::uint32_t> idx;
  idx.reserve(std::size_t(kPatchQuads) * kPatchQuads * 6);
  auto at = [](int i, int j) { return std::uint32_t(j * (kPatchQuads + 1) + i); };
  for (int j = 0; j < kPatchQuads; ++j)
    for (int i = 0; i < kPatchQuads; ++i) {
      idx.insert(idx.end(), {at(i, j), at(i + 1, j + 1), at(i + 1, j)});
      idx.insert(idx.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  return idx;
}

}  // namespace engine::terrain
