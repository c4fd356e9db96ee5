#include "terrain/terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <sstream>
#include <vector>

namespace engine::terrain {
namespace {

// Probe estimates of the noise's error are scaled by this: the probes see a few
// thousand samples of a field with hundreds of millions, so the true maximum can
// be somewhat above the probed one.
constexpr double kProbeSafety = 1.5;
constexpr int kErrorProbes = 16;

std::string describe(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Status validate(const TerrainSettings& s, const std::string& where) {
  if (!std::isfinite(s.size) || s.size <= 0.0)
    return makeError(where + ": size must be a finite number > 0 (got " + describe(s.size) + ")");
  if (!std::isfinite(s.heightScale) || s.heightScale < 0.0)
    return makeError(where + ": heightScale must be a finite number >= 0 (got " +
                     describe(s.heightScale) + ")");
  if (!finite(s.origin)) return makeError(where + ": origin must be finite");
  if (s.pageCacheBytes < kPageBytes * 4)
    return makeError(where + ": pageCacheBytes " + std::to_string(s.pageCacheBytes) +
                     " is under four pages (" + std::to_string(kPageBytes * 4) + " bytes)");
  if (s.heightmap.empty()) {
    if (!std::isfinite(s.spacing) || s.spacing <= 0.0)
      return makeError(where + ": spacing must be a finite number > 0 (got " + describe(s.spacing) + ")");
    const double cells = std::ceil(s.size / s.spacing - 1e-9);
    if (cells > kMaxCellsPerSide)
      return makeError(where + ": size / spacing gives " + describe(cells) +
                       " cells a side; at most " + std::to_string(kMaxCellsPerSide) + " are supported");
    if (s.octaves < 1 || s.octaves > 24)
      return makeError(where + ": octaves must be in [1, 24] (got " + std::to_string(s.octaves) + ")");
    if (!std::isfinite(s.featureSize) || s.featureSize < 0.0)
      return makeError(where + ": featureSize must be a finite number >= 0");
  }
  return Ok{};
}

// Side, in cells, of the blocks whose exact errors Terrain::meshError keeps: one
// level-1 node, in which every level up to kExactErrorLevels has whole quads.
constexpr int kBlockCells = 2 * kNodeQuads;
static_assert(kBlockCells % (1 << kExactErrorLevels) == 0);

std::int64_t blockKey(int bx, int bz) { return std::int64_t(bx) << 32 | std::uint32_t(bz); }

// Height of the level-`level` mesh over full-resolution sample (x, z): its vertices
// sit every stride samples, clamped to the field's edge as the drawn grid's are,
// and each quad is split along its (0,0)-(1,1) diagonal, as patchIndices() draws it.
template <typename At>
double levelMeshHeight(const At& at, int level, int x, int z, int cellsX, int cellsZ) {
  const int s = 1 << level;
  const int x0 = x / s * s, z0 = z / s * s;
  const int x1 = std::min(x0 + s, cellsX), z1 = std::min(z0 + s, cellsZ);
  const double u = x1 > x0 ? double(x - x0) / (x1 - x0) : 0.0;
  const double v = z1 > z0 ? double(z - z0) / (z1 - z0) : 0.0;
  const double h00 = at(x0, z0), h11 = at(x1, z1);
  if (u >= v) {
    const double h10 = at(x1, z0);
    return h00 + (h10 - h00) * u + (h11 - h10) * v;
  }
  const double h01 = at(x0, z1);
  return h00 + (h11 - h01) * u + (h01 - h00) * v;
}

int floorPow2(double v) {
  int p = 1;
  while (p <= kMaxCellsPerSide && double(p) * 2.0 <= v) p *= 2;
  return p;
}

}  // namespace

Result<Terrain> Terrain::create(const TerrainSettings& settings) {
  const std::string where = settings.heightmap.empty() ? std::string("terrain") : settings.heightmap;
  if (Status ok = validate(settings, where); !ok) return ok.error();
  Terrain t;
  t.origin_ = settings.origin;
  const float heightScale = float(settings.heightScale);
  if (settings.heightmap.empty()) {
    t.spacing_ = settings.spacing;
    t.cellsX_ = t.cellsZ_ = std::max(1, int(std::ceil(settings.size / settings.spacing - 1e-9)));
    const double feature = settings.featureSize > 0.0 ? settings.featureSize : settings.size / 4.0;
    NoiseParams noise;
    noise.seed = settings.seed;
    noise.basePeriod = std::max(2, floorPow2(feature / settings.spacing));
    noise.octaves = settings.octaves;
    noise.heightScale = heightScale;
    t.source_ = std::make_unique<NoiseHeights>(noise);
  } else {
    auto image = loadHeightmap(settings.heightmap, heightScale);
    if (!image) return image.error();
    t.cellsX_ = image.value()->width() - 1;
    t.cellsZ_ = image.value()->height() - 1;
    t.spacing_ = settings.size / std::max(t.cellsX_, t.cellsZ_);
    t.source_ = std::move(image).value();
  }
  while ((double(kNodeQuads) * stride(t.levelCount_ - 1)) < std::max(t.cellsX_, t.cellsZ_)) {
    ++t.levelCount_;
  }
  // The generator must not capture `this`: a Terrain moves. The source lives on
  // the heap and does not.
  const HeightSource* source = t.source_.get();
  const int cellsX = t.cellsX_, cellsZ = t.cellsZ_;
  t.cache_ = std::make_unique<PageCache>(
      settings.pageCacheBytes, [source, cellsX, cellsZ](const PageKey& key, HeightPage& page) {
        const int s = stride(key.level);
        const int gx0 = key.nx * kNodeQuads * s, gz0 = key.nz * kNodeQuads * s;
        std::array<int, kPageSide> xs, zs;
        for (int i = -1; i < kPageSide - 1; ++i) {
          xs[std::size_t(i + 1)] = std::clamp(gx0 + i * s, 0, cellsX);
          zs[std::size_t(i + 1)] = std::clamp(gz0 + i * s, 0, cellsZ);
        }
        source->sampleGrid(xs, zs, std::span<float>(page.heights).first(kPageSamples));
      });
  t.estimateErrors(!settings.heightmap.empty());
  t.blockErrors_ = std::make_unique<std::unordered_map<std::int64_t, BlockErrors>>();
  return t;
}

float Terrain::sample(int ix, int iz) const {
  return source_->sample(std::clamp(ix, 0, cellsX_), std::clamp(iz, 0, cellsZ_));
}

HeightRange Terrain::nodeBounds(const PageKey& node) const {
  const int span = kNodeQuads * stride(node.level);
  return regionBounds(node.nx * span, node.nz * span, node.nx * span + span, node.nz * span + span);
}

HeightRange Terrain::regionBounds(int x0, int z0, int x1, int z1) const {
  return source_->bounds(std::clamp(x0, 0, cellsX_), std::clamp(z0, 0, cellsZ_),
                         std::clamp(x1, 0, cellsX_), std::clamp(z1, 0, cellsZ_));
}

// The largest difference, over the level-(L-1) vertices of a region, between the
// level-(L-1) mesh and the level-L mesh. The two meshes are piecewise linear and
// every level-L triangle is a union of level-(L-1) triangles (same diagonal
// direction), so the difference peaks at level-(L-1) vertices, and the sum of these
// increments over levels bounds the error against full resolution.
double Terrain::deltaOverRegion(int level, int gx0, int gz0, int cells) const {
  const int s = stride(level - 1);
  // The region's samples, a border of one around it: one grid where it is small (the
  // probes: the noise hashes each lattice point once for it), point by point where it
  // is the whole field (an exact estimate reads a heightmap, whose samples are array
  // reads and whose grid would be as large as the image).
  constexpr std::size_t kMaxGrid = 1u << 16;
  const std::size_t side = std::size_t(cells) + 3;
  std::vector<int> xs, zs;
  std::vector<float> grid;
  if (side * side <= kMaxGrid) {
    for (int a = -1; a <= cells + 1; ++a) {
      xs.push_back(std::clamp(gx0 + a * s, 0, cellsX_));
      zs.push_back(std::clamp(gz0 + a * s, 0, cellsZ_));
    }
    grid.resize(side * side);
    source_->sampleGrid(xs, zs, grid);
  }
  // Sample (gx0 + a * s, gz0 + b * s), a and b from -1 to cells + 1.
  const auto at = [&](int a, int b) {
    return grid.empty() ? double(sample(gx0 + a * s, gz0 + b * s)) : double(grid[std::size_t(b + 1) * side + std::size_t(a + 1)]);
  };
  double worst = 0.0;
  for (int b = 0; b <= cells; ++b) {
    const int gz = gz0 + b * s;
    if (gz > cellsZ_) break;
    const bool oddZ = (gz / s) % 2 != 0;
    for (int a = 0; a <= cells; ++a) {
      const int gx = gx0 + a * s;
      if (gx > cellsX_) break;
      const bool oddX = (gx / s) % 2 != 0;
      if (!oddX && !oddZ) continue;
      const int da = oddX ? 1 : 0, db = oddZ ? 1 : 0;
      // Odd in both: the point sits on the level-L quad's (0,0)-(1,1) diagonal.
      const double coarse = 0.5 * (at(a - da, b - db) + at(a + da, b + db));
      worst = std::max(worst, std::abs(at(a, b) - coarse));
    }
  }
  return worst;
}

void Terrain::estimateErrors(bool exact) {
  errors_.assign(std::size_t(levelCount_), 0.0f);
  double sum = 0.0;
  for (int level = 1; level < levelCount_; ++level) {
    double delta = 0.0;
    if (exact) {
      delta = deltaOverRegion(level, 0, 0, std::max(cellsX_, cellsZ_) / stride(level - 1) + 1);
    } else {
      // Probes of 64x64 level-(L-1) cells at hashed, aligned places in the field.
      const int span = kNodeQuads * stride(level - 1);
      const int placesX = std::max(1, cellsX_ / span), placesZ = std::max(1, cellsZ_ / span);
      for (int p = 0; p < kErrorProbes; ++p) {
        const double u = 0.5 * (latticeValue(0x7E44A1u, level, p, 0) + 1.0);
        const double v = 0.5 * (latticeValue(0x7E44A1u, level, p, 1) + 1.0);
        const int px = std::min(placesX - 1, int(u * placesX)), pz = std::min(placesZ - 1, int(v * placesZ));
        delta = std::max(delta, kProbeSafety * deltaOverRegion(level, px * span, pz * span, kNodeQuads));
      }
    }
    sum += delta;
    errors_[std::size_t(level)] = float(sum);
  }
}

Terrain::BlockErrors Terrain::scanBlock(int bx, int bz) const {
  // The block's samples once, as one grid (the noise hashes each lattice point once
  // for it), then every level's mesh against them.
  const int x0 = bx * kBlockCells, z0 = bz * kBlockCells;
  const int w = std::min(kBlockCells, cellsX_ - x0), d = std::min(kBlockCells, cellsZ_ - z0);
  // Read a coarsest quad beyond the far edges too: a sample there is also the low
  // edge of the next cell, whose far corners the mesh height reads.
  const int rw = std::min(w + stride(kExactErrorLevels), cellsX_ - x0);
  const int rd = std::min(d + stride(kExactErrorLevels), cellsZ_ - z0);
  const std::size_t row = std::size_t(rw + 1);
  std::vector<float> heights(row * std::size_t(rd + 1));
  std::vector<int> xs(row), zs(std::size_t(rd + 1));
  for (std::size_t x = 0; x < xs.size(); ++x) xs[x] = x0 + int(x);
  for (std::size_t z = 0; z < zs.size(); ++z) zs[z] = z0 + int(z);
  source_->sampleGrid(xs, zs, heights);
  auto at = [&](int x, int z) { return double(heights[std::size_t(z - z0) * row + std::size_t(x - x0)]); };
  BlockErrors errors{};
  for (int level = 1; level <= kExactErrorLevels; ++level) {
    double worst = 0.0;
    for (int z = z0; z <= z0 + d; ++z)
      for (int x = x0; x <= x0 + w; ++x)
        worst = std::max(worst, std::abs(levelMeshHeight(at, level, x, z, cellsX_, cellsZ_) - at(x, z)));
    errors[std::size_t(level - 1)] = float(worst);
  }
  return errors;
}

bool Terrain::measureErrors(const PageKey& block) const {
  if (block.nx < 0 || block.nz < 0 || block.nx * kBlockCells >= cellsX_ || block.nz * kBlockCells >= cellsZ_) return false;
  if (errorsMeasured(block)) return false;
  blockErrors_->emplace(blockKey(block.nx, block.nz), scanBlock(block.nx, block.nz));
  return true;
}

bool Terrain::errorsMeasured(const PageKey& block) const {
  return blockErrors_->count(blockKey(block.nx, block.nz)) != 0;
}

float Terrain::meshError(int level, const PageKey& region) const {
  if (level == 0) return 0.0f;
  if (level > kExactErrorLevels) return geometricError(level);
  // A level-0 region lies in one block; a level-L one spans 2^(L-1) a side.
  const int blocks = region.level == 0 ? 1 : stride(region.level - 1);
  const int bx0 = region.level == 0 ? region.nx / 2 : region.nx * blocks;
  const int bz0 = region.level == 0 ? region.nz / 2 : region.nz * blocks;
  float worst = 0.0f;
  for (int bz = bz0; bz < bz0 + blocks; ++bz)
    for (int bx = bx0; bx < bx0 + blocks; ++bx) {
      if (bx * kBlockCells >= cellsX_ || bz * kBlockCells >= cellsZ_) continue;  // past the field
      const auto it = blockErrors_->find(blockKey(bx, bz));
      worst = std::max(worst, it == blockErrors_->end() ? geometricError(level) : it->second[std::size_t(level - 1)]);
    }
  return worst;
}

double Terrain::heightAt(double x, double z) const {
  const double u = std::clamp((x - origin_.x) / spacing_, 0.0, double(cellsX_));
  const double v = std::clamp((z - origin_.z) / spacing_, 0.0, double(cellsZ_));
  const int cx = std::min(int(u), cellsX_ - 1), cz = std::min(int(v), cellsZ_ - 1);
  const double fx = u - cx, fz = v - cz;
  auto p = page({0, cx / kNodeQuads, cz / kNodeQuads});
  const int i = cx % kNodeQuads, j = cz % kNodeQuads;
  const double a = p->at(i, j) + (p->at(i + 1, j) - double(p->at(i, j))) * fx;
  const double b = p->at(i, j + 1) + (p->at(i + 1, j + 1) - double(p->at(i, j + 1))) * fx;
  return origin_.y + a + (b - a) * fz;
}

glm::vec3 Terrain::normalAt(double x, double z) const {
  const double u = std::clamp((x - origin_.x) / spacing_, 0.0, double(cellsX_));
  const double v = std::clamp((z - origin_.z) / spacing_, 0.0, double(cellsZ_));
  const int cx = std::min(int(u), cellsX_ - 1), cz = std::min(int(v), cellsZ_ - 1);
  const float fx = float(u - cx), fz = float(v - cz);
  auto p = page({0, cx / kNodeQuads, cz / kNodeQuads});
  const int i0 = cx % kNodeQuads, j0 = cz % kNodeQuads;
  // Central differences; the page's one-sample border supplies the neighbours.
  auto corner = [&](int i, int j) {
    return glm::normalize(glm::vec3(p->at(i - 1, j) - p->at(i + 1, j), float(2.0 * spacing_),
                                    p->at(i, j - 1) - p->at(i, j + 1)));
  };
  const glm::vec3 a = glm::mix(corner(i0, j0), corner(i0 + 1, j0), fx);
  const glm::vec3 b = glm::mix(corner(i0, j0 + 1), corner(i0 + 1, j0 + 1), fx);
  return glm::normalize(glm::mix(a, b, fz));
}

}  // namespace engine::terrain
