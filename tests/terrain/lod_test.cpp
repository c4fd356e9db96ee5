// CDLOD without GL: crack-freedom at every level transition (exact equality of the
// CPU mirror of the vertex shader), rendered surface within the stated error,
// screen-space ranges and frustum culling.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "core/image.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain_support.h"

using namespace engine;
using namespace engine::terrain;
using engine::terrain::test::makeCamera;
using engine::terrain::test::settledSelection;

namespace {

using Point = std::array<float, 3>;
using Edge = std::array<float, 6>;

Edge edgeKey(const glm::vec3& a, const glm::vec3& b) {
  Point pa{a.x, a.y, a.z}, pb{b.x, b.y, b.z};
  if (pb < pa) std::swap(pa, pb);
  return {pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]};
}

struct CrackReport {
  std::size_t edges = 0;
  std::size_t unmatched = 0;
  std::set<int> levels;
};

// Watertightness: every boundary edge of every patch (after morphing, ignoring the
// zero-length edges that fully morphed vertices leave) must appear, bit for bit,
// in exactly one other patch, unless it lies on the field's border.
CrackReport checkWatertight(const Terrain& terrain, const LodSelection& selection) {
  std::map<Edge, int> count;
  CrackReport report;
  const int n = kPatchQuads;
  for (const LodPatch& p : selection.patches) {
    report.levels.insert(p.level);
    const std::vector<glm::vec3> v = patchVertices(terrain, selection, p);
    auto at = [&](int i, int j) { return v[std::size_t(j) * (n + 1) + i]; };
    const int span = n * Terrain::stride(p.level);
    const bool border[4] = {p.gz == 0, p.gx + span >= terrain.cellsX(), p.gz + span >= terrain.cellsZ(), p.gx == 0};
    for (int side = 0; side < 4; ++side) {
      if (border[side]) continue;
      for (int t = 0; t < n; ++t) {
        glm::vec3 a, b;
        switch (side) {
          case 0: a = at(t, 0), b = at(t + 1, 0); break;
          case 1: a = at(n, t), b = at(n, t + 1); break;
          case 2: a = at(t, n), b = at(t + 1, n); break;
          default: a = at(0, t), b = at(0, t + 1); break;
        }
        if (a == b) continue;
        ++count[edgeKey(a, b)];
      }
    }
  }
  for (const auto& [edge, c] : count) {
    ++report.edges;
    if (c != 2) ++report.unmatched;
  }
  return report;
}

// Larger of the two twists of the full-resolution cells around (u, v): how far a
// bilinear patch can be from its two triangles.
double twistAround(const Terrain& t, double u, double v) {
  const int cx = int(std::floor(u)), cz = int(std::floor(v));
  double worst = 0.0;
  for (int dz = -1; dz <= 0; ++dz)
    for (int dx = -1; dx <= 0; ++dx) {
      const int x = cx + dx, z = cz + dz;
      worst = std::max(worst, std::abs(double(t.sample(x, z)) + t.sample(x + 1, z + 1) - t.sample(x + 1, z) -
                                       t.sample(x, z + 1)));
    }
  return worst;
}

struct Case {
  const char* name;
  glm::dvec3 eye;
  glm::dvec3 target;
};

std::vector<Case> cameraCases(const glm::dvec3& o, const Terrain& t) {
  auto ground = [&](double x, double z) { return glm::dvec3(o.x + x, t.heightAt(o.x + x, o.z + z), o.z + z); };
  return {
      {"low in the middle", ground(2048, 2048) + glm::dvec3(0, 5, 0), ground(2500, 2300)},
      {"near a corner", ground(60, 70) + glm::dvec3(0, 20, 0), ground(1000, 900)},
      {"between samples", ground(1234.37, 3011.81) + glm::dvec3(0.1, 2.3, 0.2), ground(1000, 3500)},
      {"high above", ground(1500, 2500) + glm::dvec3(0, 1500, 0), ground(2000, 2000)},
      {"outside the field", o + glm::dvec3(-600, 700, 4500), ground(2000, 2000)},
  };
}

Result<Terrain> makeNoise(glm::dvec3 origin) {
  return Terrain::create(test::noiseSettings(4096.0, 600.0, origin));
}

// The 1-pixel selection from 3 m above the ground at (2000, 2000), looking along +x.
LodSelection selectionNearTheGround(const Terrain& t) {
  const glm::dvec3 eye(2000.0, t.heightAt(2000.0, 2000.0) + 3.0, 2000.0);
  return selectLod(t, makeCamera(eye, eye + glm::dvec3(1, 0, 0)), 1.0);
}

}  // namespace

class LodCracks : public ::testing::TestWithParam<glm::dvec3> {};

TEST_P(LodCracks, SharedEdgesMatchExactlyAtEveryTransition) {
  const glm::dvec3 origin = GetParam();
  auto t = makeNoise(origin);
  ASSERT_TRUE(t.ok()) << t.error().message;
  for (const Case& c : cameraCases(origin, *t)) {
    for (double pixels : {1.0, 8.0}) {
      LodCamera camera = makeCamera(c.eye, c.target);
      camera.cull = false;  // culled neighbours would leave edges unmatched by design
      // Settled: the ranges that the measured block errors give, the tightest.
      const LodSelection selection = settledSelection(*t, camera, pixels);
      const CrackReport r = checkWatertight(*t, selection);
      EXPECT_EQ(r.unmatched, 0u) << c.name << ", " << pixels << " px: " << r.unmatched << " of " << r.edges
                                 << " boundary edges unmatched";
      EXPECT_GT(r.edges, 0u);
      if (std::string(c.name) == "low in the middle" && pixels == 8.0) {
        EXPECT_GE(r.levels.size(), 3u) << "the case should cross several level transitions";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Origins, LodCracks,
                         ::testing::Values(glm::dvec3(0.0), glm::dvec3(1.0e7, -800.0, -4.0e6)));

TEST(Lod, HeightmapWithRaggedEdgesIsWatertight) {
  // 301 x 197 samples: nodes hang over the field's edge and are clamped to it.
  Image image(301, 197);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = p[1] = p[2] = std::uint8_t(128 + 100 * std::sin(x * 0.05) * std::cos(y * 0.07));
      p[3] = 255;
    }
  const auto path = std::filesystem::temp_directory_path() / "engine_terrain_ragged.png";
  ASSERT_TRUE(writePng(path.string(), image).ok());
  TerrainSettings s;
  s.heightmap = path.string();
  s.size = 3000.0;
  s.heightScale = 300.0;
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  LodCamera camera = makeCamera({500.0, 250.0, 900.0}, {2000.0, 100.0, 1500.0});
  camera.cull = false;
  const LodSelection selection = settledSelection(*t, camera, 1.0);
  const CrackReport r = checkWatertight(*t, selection);
  EXPECT_EQ(r.unmatched, 0u) << r.unmatched << " of " << r.edges;
  EXPECT_GE(r.levels.size(), 2u);
}

// Every rendered vertex lies on its level's mesh, so it is within that level's
// stated geometric error of the full-resolution mesh; heightAt (bilinear) can be
// a further cell twist away from the triangles.
TEST(Lod, RenderedSurfaceIsWithinTheStatedErrorOfHeightAt) {
  for (glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(-2.5e6, 300.0, 8.0e6)}) {
    auto t = makeNoise(origin);
    ASSERT_TRUE(t.ok()) << t.error().message;
    for (const Case& c : cameraCases(origin, *t)) {
      LodCamera camera = makeCamera(c.eye, c.target);
      const LodSelection selection = selectLod(*t, camera, 1.0);
      double worstRatio = 0.0;
      for (std::size_t pi = 0; pi < selection.patches.size(); pi += 5) {
        const LodPatch& p = selection.patches[pi];
        const auto v = patchVertices(*t, selection, p);
        for (std::size_t i = 0; i < v.size(); i += 7) {
          const double wx = c.eye.x + v[i].x, wz = c.eye.z + v[i].z;
          const double rendered = c.eye.y + v[i].y;
          const double u = (wx - origin.x) / t->spacing(), w = (wz - origin.z) / t->spacing();
          const double allowed = t->geometricError(p.level) + twistAround(*t, u, w) + 0.02;
          const double off = std::abs(rendered - t->heightAt(wx, wz));
          worstRatio = std::max(worstRatio, off / allowed);
          ASSERT_LE(off, allowed) << c.name << ": level " << p.level << " vertex " << i;
        }
      }
      EXPECT_LE(worstRatio, 1.0);
    }
  }
}

TEST(Lod, UnmorphedVerticesSitExactlyOnSamples) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const LodSelection selection = selectionNearTheGround(*t);
  std::size_t checked = 0;
  for (const LodPatch& p : selection.patches) {
    const auto page = t->page(p.node);
    for (int j = 0; j <= kPatchQuads; j += 5)
      for (int i = 0; i <= kPatchQuads; i += 5) {
        const int s = Terrain::stride(p.level);
        if (morphFactor(selection, p.level, p.gx + i * s, p.gz + j * s) != 0.0f) continue;
        const glm::vec3 v = patchVertex(selection, p, *page, i, j);
        EXPECT_NEAR(v.y + selection.cameraHeight, t->sample(p.gx + i * s, p.gz + j * s), 1e-3);
        ++checked;
      }
  }
  EXPECT_GT(checked, 100u);
}

// patchNormal mirrors terrain.vert's v_normal: at unmorphed full-resolution
// vertices it is the central-difference normal that Terrain::normalAt gives there,
// and every normal is unit length and points up.
TEST(Lod, PatchNormalsAreTheTerrainsCentralDifferences) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const LodSelection selection = selectionNearTheGround(*t);
  std::size_t checked = 0;
  for (const LodPatch& p : selection.patches) {
    const std::vector<glm::vec3> normals = patchNormals(*t, selection, p);
    ASSERT_EQ(normals.size(), std::size_t(kPatchQuads + 1) * (kPatchQuads + 1));
    for (const glm::vec3& n : normals) {
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
      EXPECT_GT(n.y, 0.0f);
    }
    if (p.level != 0) continue;
    for (int j = 1; j < kPatchQuads; j += 3)
      for (int i = 1; i < kPatchQuads; i += 3) {
        if (morphFactor(selection, 0, p.gx + i, p.gz + j) != 0.0f) continue;
        const glm::vec3 n = normals[std::size_t(j * (kPatchQuads + 1) + i)];
        const glm::vec3 expected = t->normalAt(t->origin().x + (p.gx + i) * t->spacing(),
                                               t->origin().z + (p.gz + j) * t->spacing());
        EXPECT_NEAR(glm::dot(n, expected), 1.0f, 1e-5f);
        ++checked;
      }
  }
  EXPECT_GT(checked, 100u);
}

// Nearest distance from the camera to a patch, in the selection's metric (the
// horizontal distance and the camera's height outside the height range).
double nearestToPatch(const Terrain& t, const LodSelection& s, const LodCamera& camera, const LodPatch& p) {
  const int span = kPatchQuads * Terrain::stride(p.level);
  const glm::dvec2 cam = glm::dvec2(camera.position.x - t.origin().x, camera.position.z - t.origin().z) / t.spacing();
  const double dx = std::max({double(p.gx) - cam.x, 0.0, cam.x - std::min(p.gx + span, t.cellsX())});
  const double dz = std::max({double(p.gz) - cam.y, 0.0, cam.y - std::min(p.gz + span, t.cellsZ())});
  return std::sqrt((dx * dx + dz * dz) * t.spacing() * t.spacing() + double(s.morphDy2));
}

// Whether any of the patch's vertices morph: the farthest point is a corner.
bool morphsAnywhere(const LodSelection& s, const LodPatch& p) {
  const int span = kPatchQuads * Terrain::stride(p.level);
  for (int c = 0; c < 4; ++c)
    if (morphFactor(s, p.level, p.gx + (c & 1) * span, p.gz + (c >> 1) * span) > 0.0f) return true;
  return false;
}

TEST(Lod, FinerTargetsDrawMoreAndErrOnlyWithinTarget) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const glm::dvec3 eye(1000.0, t->heightAt(1000.0, 1000.0) + 10.0, 1000.0);
  const LodCamera camera = makeCamera(eye, eye + glm::dvec3(1, -0.1, 1));
  settledSelection(*t, camera, 0.5);  // the finest target's reach holds every other's
  std::size_t previous = SIZE_MAX;
  for (double pixels : {0.5, 1.0, 2.0, 4.0, 8.0}) {
    const LodSelection s = selectLod(*t, camera, pixels);
    EXPECT_EQ(s.stats.blocksPending, 0u);
    EXPECT_LE(s.stats.triangles, previous) << pixels;
    previous = s.stats.triangles;
    // Each patch's mesh error projects under target wherever it shows: its own
    // level's from its nearest point on, the next level's (where it morphs) not
    // before the morph starts: error * pixelsPerMetreAt1m <= target * distance.
    const double k = camera.viewportHeight / (2.0 * std::tan(camera.fovY / 2));
    for (const LodPatch& p : s.patches) {
      const double d = nearestToPatch(*t, s, camera, p);
      const PageKey area = patchArea(p);
      EXPECT_LE(t->meshError(p.level, area) * k, pixels * 1.0001 * d) << "level " << p.level;
      if (p.level + 1 >= t->levelCount() || !morphsAnywhere(s, p)) continue;
      const double morphing = std::max(d, double(s.morphStart[std::size_t(p.level)]));
      EXPECT_LE(t->meshError(p.level + 1, area) * k, pixels * 1.0001 * morphing) << "level " << p.level;
    }
  }
}

// The sun's maps select with the light's box for culling and must morph as the
// view does; and turning the camera must not change the mesh.
TEST(Lod, RangesDependOnThePositionNotTheDirectionOrCulling) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const glm::dvec3 eye(1500.0, t->heightAt(1500.0, 2200.0) + 25.0, 2200.0);
  LodCamera ahead = makeCamera(eye, eye + glm::dvec3(1, -0.1, 0.3));
  measureBlocks(*t, ahead, 1.0, 40);  // part measured: the mix must agree too
  LodCamera behind = makeCamera(eye, eye + glm::dvec3(-0.2, -0.4, -1));
  LodCamera all = ahead;
  all.cull = false;
  const LodSelection a = selectLod(*t, ahead, 1.0), b = selectLod(*t, behind, 1.0), c = selectLod(*t, all, 1.0);
  EXPECT_GT(a.stats.blocksPending, 0u);
  EXPECT_EQ(a.stats.blocksPending, b.stats.blocksPending);
  for (const LodSelection* other : {&b, &c}) {
    EXPECT_EQ(a.range, other->range);
    EXPECT_EQ(a.morphStart, other->morphStart);
    EXPECT_EQ(a.morphEnd, other->morphEnd);
  }
  EXPECT_NE(a.patches.size(), b.patches.size());  // different views all the same
}

// Selections only read the blocks' errors; measuring them, nearest first, takes a
// view from the level-wide estimate to its settled ranges (here all shorter: most
// blocks are far smoother than the field's roughest).
TEST(Lod, MeasuringBlocksSettlesTheRanges) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const glm::dvec3 eye(2500.0, t->heightAt(2500.0, 1200.0) + 15.0, 1200.0);
  const LodCamera camera = makeCamera(eye, eye + glm::dvec3(-1, -0.2, 0.4));
  const LodSelection estimated = selectLod(*t, camera, 1.0);
  EXPECT_EQ(selectLod(*t, camera, 1.0).stats.blocksPending, estimated.stats.blocksPending);
  const std::size_t left = measureBlocks(*t, camera, 1.0, 10);
  EXPECT_EQ(left, estimated.stats.blocksPending - 10);
  EXPECT_EQ(selectLod(*t, camera, 1.0).stats.blocksPending, left);
  EXPECT_EQ(measureBlocks(*t, camera, 1.0, SIZE_MAX), 0u);
  const LodSelection settled = selectLod(*t, camera, 1.0);
  EXPECT_EQ(settled.stats.blocksPending, 0u);
  for (int level = 0; level + 1 < t->levelCount(); ++level)
    EXPECT_LE(settled.range[std::size_t(level)], estimated.range[std::size_t(level)]) << "level " << level;
  EXPECT_LT(settled.stats.triangles, estimated.stats.triangles);
}

TEST(Lod, PageBudgetCoarsensTheTargetInsteadOfDroppingPatches) {
  auto t = makeNoise(glm::dvec3(0.0));
  ASSERT_TRUE(t.ok());
  const glm::dvec3 eye(1000.0, t->heightAt(1000.0, 1000.0) + 10.0, 1000.0);
  const LodCamera camera = makeCamera(eye, eye + glm::dvec3(1, -0.1, 1));
  // Settled first, so that every selection below sees the same block errors.
  const LodSelection fine = settledSelection(*t, camera, 0.5);
  // stats.pages counts distinct nodes.
  std::set<std::array<int, 3>> nodes;
  for (const LodPatch& p : fine.patches) nodes.insert({p.node.level, p.node.nx, p.node.nz});
  EXPECT_EQ(fine.stats.pages, nodes.size());

  // A budget the full target fits: nothing changes.
  const LodSelection same = selectLodWithin(*t, camera, 0.5, fine.stats.pages);
  EXPECT_EQ(same.stats.coarsenings, 0);
  EXPECT_EQ(same.patches.size(), fine.patches.size());
  EXPECT_EQ(same.stats.targetPixels, 0.5);

  // Half of it: a coarser target, each step by kCoarsenStep, that fits.
  const std::size_t budget = fine.stats.pages / 2;
  const LodSelection fitted = selectLodWithin(*t, camera, 0.5, budget);
  EXPECT_GT(fitted.stats.coarsenings, 0);
  EXPECT_LE(fitted.stats.pages, budget);
  EXPECT_NEAR(fitted.stats.targetPixels, 0.5 * std::pow(kCoarsenStep, fitted.stats.coarsenings), 1e-9);
  // The step before did not fit, so the target is the finest that does.
  const LodSelection before = selectLod(*t, camera, fitted.stats.targetPixels / kCoarsenStep);
  EXPECT_GT(before.stats.pages, budget);
  // Coarser: fewer triangles, no smaller a stated error.
  EXPECT_LT(fitted.stats.triangles, fine.stats.triangles);
  EXPECT_GE(fitted.stats.maxGeometricError, fine.stats.maxGeometricError);

  // An impossible budget ends (the ranges have a floor), reporting what it needs.
  const LodSelection impossible = selectLodWithin(*t, camera, 0.5, 1);
  EXPECT_GT(impossible.stats.pages, 1u);
  EXPECT_GT(impossible.stats.coarsenings, 0);
}

TEST(Frustum, BoxesAgainstPlanes) {
  // Looking down -z from the origin, 90 degrees, near 1, far 100.
  const glm::mat4 vp = glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 100.0f);
  const Frustum f = Frustum::fromViewProjection(vp);
  EXPECT_TRUE(f.intersects({-1, -1, -11}, {1, 1, -9}));        // straight ahead
  EXPECT_FALSE(f.intersects({-1, -1, 9}, {1, 1, 11}));         // behind
  EXPECT_FALSE(f.intersects({-31, -1, -11}, {-29, 1, -9}));    // far to the left
  EXPECT_FALSE(f.intersects({-1, 20, -11}, {1, 22, -9}));      // above
  EXPECT_FALSE(f.intersects({-1, -1, -300}, {1, 1, -200}));    // beyond the far plane
  EXPECT_TRUE(f.intersects({-100, -100, -50}, {100, 100, 50})); // contains the frustum's apex
  EXPECT_TRUE(f.intersects({9, -1, -11}, {12, 1, -9}));        // straddles the right plane
}

TEST(Frustum, ReverseZeroToOneDepthCullsBeyondTheFarPlane) {
  // The scene renderer's projection: reverse-Z (near at depth 1, far at 0), clip
  // depth 0..w. Read with GL's -w..w planes it would keep everything past far.
  const glm::mat4 vp = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 100.0f, 1.0f);
  const Frustum f = Frustum::fromViewProjection(vp, true);
  EXPECT_TRUE(f.intersects({-1, -1, -11}, {1, 1, -9}));       // straight ahead
  EXPECT_TRUE(f.intersects({-1, -1, -99.5}, {1, 1, -98}));    // just inside far
  EXPECT_FALSE(f.intersects({-1, -1, -300}, {1, 1, -200}));   // beyond the far plane
  EXPECT_FALSE(f.intersects({-1, -1, -0.8}, {1, 1, -0.5}));   // nearer than near
  EXPECT_FALSE(f.intersects({-1, -1, 9}, {1, 1, 11}));        // behind
  // Why the flag exists: GL's planes on this matrix keep the box beyond far.
  EXPECT_TRUE(Frustum::fromViewProjection(vp, false).intersects({-1, -1, -300}, {1, 1, -200}));
}

// Culling only removes patches, and only ones wholly outside the view: each has
// all its vertices beyond one clip plane.
TEST(Frustum, CulledPatchesAreWhollyOutside) {
  auto t = makeNoise(glm::dvec3(3.0e6, 0.0, 3.0e6));
  ASSERT_TRUE(t.ok());
  const glm::dvec3 o = t->origin();
  const glm::dvec3 eye(o.x + 1500.0, t->heightAt(o.x + 1500.0, o.z + 800.0) + 40.0, o.z + 800.0);
  LodCamera camera = makeCamera(eye, eye + glm::dvec3(0.3, -0.2, 1.0));
  const LodSelection culled = selectLod(*t, camera, 1.0);
  camera.cull = false;
  const LodSelection all = selectLod(*t, camera, 1.0);
  auto key = [](const LodPatch& p) { return std::array<int, 3>{p.level, p.gx, p.gz}; };
  std::set<std::array<int, 3>> kept;
  for (const LodPatch& p : culled.patches) kept.insert(key(p));
  std::set<std::array<int, 3>> everything;
  for (const LodPatch& p : all.patches) everything.insert(key(p));
  for (const auto& k : kept) EXPECT_TRUE(everything.count(k)) << "culling added a patch";
  EXPECT_LT(culled.patches.size(), all.patches.size() * 3 / 4);
  std::size_t dropped = 0;
  for (const LodPatch& p : all.patches) {
    if (kept.count(key(p))) continue;
    ++dropped;
    const auto v = patchVertices(*t, all, p);
    bool outsideOne = false;
    for (int plane = 0; plane < 6 && !outsideOne; ++plane) {
      bool allOut = true;
      for (const glm::vec3& x : v) {
        const glm::vec4 c = camera.viewProjection * glm::vec4(x, 1.0f);
        const float s = plane % 2 ? -1.0f : 1.0f;
        if (c.w + s * c[plane / 2] >= 0.0f) {
          allOut = false;
          break;
        }
      }
      outsideOne = allOut;
    }
    EXPECT_TRUE(outsideOne) << "patch at level " << p.level << " (" << p.gx << ", " << p.gz
                            << ") was culled but reaches into the view";
  }
  EXPECT_GT(dropped, 0u);
}
