// Height fields without GL: procedural determinism, bilinear queries, PNG loading
// (8 and 16 bit), bad input and the page cache's memory budget.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/image.h"
#include "terrain/height_source.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain_support.h"

using namespace engine;
using namespace engine::terrain;
namespace fs = std::filesystem;

namespace {

fs::path tempDir() {
  fs::path dir = fs::temp_directory_path() / "engine_terrain_test";
  fs::create_directories(dir);
  return dir;
}

// A minimal PNG writer for 16-bit grey (stb_image_write has no 16-bit output):
// zlib "stored" blocks, so no compressor is needed.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put32(out, std::uint32_t(data.size()));
  std::vector<std::uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  put32(out, crc32(body.data(), body.size()));
}

void writeGrey16Png(const fs::path& path, int w, int h, const std::vector<std::uint16_t>& v) {
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);  // filter: none
    for (int x = 0; x < w; ++x) {
      raw.push_back(std::uint8_t(v[std::size_t(y) * w + x] >> 8));
      raw.push_back(std::uint8_t(v[std::size_t(y) * w + x] & 0xFF));
    }
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  for (std::size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - off);
    z.push_back(off + n >= raw.size() ? 1 : 0);
    z.push_back(std::uint8_t(n & 0xFF));
    z.push_back(std::uint8_t(n >> 8));
    z.push_back(std::uint8_t(~n & 0xFF));
    z.push_back(std::uint8_t((~n >> 8) & 0xFF));
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(off), raw.begin() + std::ptrdiff_t(off + n));
    if (off + n >= raw.size()) break;
  }
  put32(z, (b << 16) | a);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  put32(ihdr, std::uint32_t(w));
  put32(ihdr, std::uint32_t(h));
  ihdr.insert(ihdr.end(), {16, 0, 0, 0, 0});  // 16 bit, grey, deflate, no filter, no interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
}

void writeGrey8Png(const fs::path& path, int w, int h, const std::vector<std::uint8_t>& v) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = p[1] = p[2] = v[std::size_t(y) * w + x];
      p[3] = 255;
    }
  ASSERT_TRUE(writePng(path.string(), image).ok());
}

Result<Terrain> noiseTerrain(double size, double heightScale, std::uint32_t seed = 7,
                             glm::dvec3 origin = glm::dvec3(0.0)) {
  TerrainSettings s = test::noiseSettings(size, heightScale, origin);
  s.seed = seed;
  return Terrain::create(s);
}

}  // namespace

TEST(TerrainNoise, LatticeHashIsFixed) {
  // Pinned values: a change here changes every procedural world.
  EXPECT_DOUBLE_EQ(latticeValue(1, 0, 0, 0), latticeValue(1, 0, 0, 0));
  const double expected[4] = {0.38702427802045847, 0.11680659275271976, -0.56518105169048249, -0.17569391162852144};
  EXPECT_NEAR(latticeValue(1, 0, 0, 0), expected[0], 1e-15);
  EXPECT_NEAR(latticeValue(1, 3, -5, 17), expected[1], 1e-15);
  EXPECT_NEAR(latticeValue(42, 0, 1000000, -1000000), expected[2], 1e-15);
  EXPECT_NEAR(latticeValue(0xFFFFFFFFu, 11, 65536, 65536), expected[3], 1e-15);
}

TEST(TerrainNoise, HeightsForASeedAreFixed) {
  auto t = noiseTerrain(4096.0, 400.0, 1234);
  ASSERT_TRUE(t.ok()) << t.error().message;
  const std::array<std::array<int, 2>, 4> at = {{{0, 0}, {1, 0}, {2048, 1000}, {4096, 4095}}};
  const float expected[4] = {149.076874f, 149.120819f, 208.696838f, 281.502197f};
  for (std::size_t i = 0; i < at.size(); ++i)
    EXPECT_NEAR(t->sample(at[i][0], at[i][1]), expected[i], 1e-4) << at[i][0] << "," << at[i][1];
  // Same seed, same heights; another seed, other heights.
  auto again = noiseTerrain(4096.0, 400.0, 1234);
  auto other = noiseTerrain(4096.0, 400.0, 1235);
  ASSERT_TRUE(again.ok() && other.ok());
  EXPECT_EQ(t->sample(777, 333), again->sample(777, 333));
  EXPECT_NE(t->sample(777, 333), other->sample(777, 333));
}

TEST(TerrainNoise, BoundsContainEverySample) {
  NoiseParams p;
  p.seed = 3;
  p.basePeriod = 512;
  p.octaves = 10;
  NoiseHeights noise(p);
  for (auto [x0, z0, n] : std::array<std::array<int, 3>, 4>{{{0, 0, 64}, {1000, 300, 32}, {4000, 4000, 128}, {5, 7, 3}}}) {
    const HeightRange r = noise.bounds(x0, z0, x0 + n, z0 + n);
    for (int z = z0; z <= z0 + n; ++z)
      for (int x = x0; x <= x0 + n; ++x) {
        const float h = noise.sample(x, z);
        ASSERT_LE(r.min, h);
        ASSERT_GE(r.max, h);
      }
  }
}

// Pages and error scans sample whole grids at once (NoiseHeights::sampleGrid hashes
// each octave's lattice values once for the grid); every sample must be the bits
// sample() gives. 2,000 random grids: seeds, base periods 2 to 4096, 1 to 12 octaves,
// origins far out on both sides of zero (negative cells divide the other way), steps
// of 1 to 300 samples, axes that repeat a coordinate (pages clamp at the field's
// edge) or go backwards, 1 to 40 samples a side. Then a clamped page's layout.
TEST(TerrainNoise, GridSamplesAreThePointSamplesBitForBit) {
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> origin(-3000000, 3000000), side(1, 40), step(1, 300), octaves(1, 12), power(1, 12);
  std::size_t compared = 0, differing = 0;
  for (int grid = 0; grid < 2000; ++grid) {
    NoiseParams p;
    p.seed = std::uint32_t(rng());
    p.basePeriod = 1 << power(rng);
    p.octaves = octaves(rng);
    p.heightScale = 250.0f;
    const NoiseHeights noise(p);
    const auto axis = [&] {
      std::vector<int> at(std::size_t(side(rng)));
      int x = grid % 3 == 0 ? std::uniform_int_distribution<int>(-40, 40)(rng) : origin(rng);
      const int dx = grid % 7 == 0 ? -step(rng) : step(rng);
      for (int& v : at) {
        v = x;
        if (rng() % 5 != 0) x += dx;  // now and then the same coordinate again
      }
      return at;
    };
    const std::vector<int> xs = axis(), zs = axis();
    std::vector<float> out(xs.size() * zs.size());
    noise.sampleGrid(xs, zs, out);
    for (std::size_t j = 0; j < zs.size(); ++j) {
      for (std::size_t i = 0; i < xs.size(); ++i) {
        ++compared;
        differing += std::bit_cast<std::uint32_t>(out[j * xs.size() + i]) !=
                     std::bit_cast<std::uint32_t>(noise.sample(xs[i], zs[j]));
      }
    }
  }
  EXPECT_EQ(differing, 0u) << "of " << compared << " samples";
  EXPECT_GT(compared, 500000u);
  // A page at a field's far corner: its last columns and rows clamp to the edge.
  NoiseParams p;
  p.seed = 9;
  const NoiseHeights noise(p);
  const std::vector<int> xs = {990, 994, 998, 1000, 1000, 1000}, zs = {0, 0, 4, 8};
  std::vector<float> out(xs.size() * zs.size());
  noise.sampleGrid(xs, zs, out);
  for (std::size_t j = 0; j < zs.size(); ++j) {
    for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_EQ(out[j * xs.size() + i], noise.sample(xs[i], zs[j]));
  }
}

TEST(TerrainQuery, BilinearIsExactAtSamplesAndBetween) {
  const glm::dvec3 origin(1.0e7, 250.0, -3.0e6);
  auto t = noiseTerrain(1024.0, 300.0, 5, origin);
  ASSERT_TRUE(t.ok()) << t.error().message;
  for (auto [ix, iz] : std::array<std::array<int, 2>, 5>{{{0, 0}, {63, 64}, {64, 64}, {500, 1023}, {1024, 1024}}}) {
    EXPECT_EQ(t->heightAt(origin.x + ix, origin.z + iz), origin.y + double(t->sample(ix, iz)));
  }
  // The middle of a cell is the mean of its corners; a third of the way along an
  // edge is the matching blend.
  const double mid = t->heightAt(origin.x + 100.5, origin.z + 200.5) - origin.y;
  const double mean = (double(t->sample(100, 200)) + t->sample(101, 200) + t->sample(100, 201) + t->sample(101, 201)) / 4.0;
  EXPECT_NEAR(mid, mean, 1e-9);
  const double edge = t->heightAt(origin.x + 100.25, origin.z + 200.0) - origin.y;
  EXPECT_NEAR(edge, 0.75 * t->sample(100, 200) + 0.25 * t->sample(101, 200), 1e-9);
  // Outside the field the edge is held.
  EXPECT_EQ(t->heightAt(origin.x - 50.0, origin.z - 50.0), origin.y + double(t->sample(0, 0)));
  // Normals point up and lean away from the rise.
  const glm::vec3 n = t->normalAt(origin.x + 300.0, origin.z + 300.0);
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  EXPECT_GT(n.y, 0.0f);
  const float dhdx = t->sample(301, 300) - t->sample(299, 300);
  if (std::abs(dhdx) > 0.05f) {
    EXPECT_LT(n.x * dhdx, 0.0f);
  }
}

TEST(TerrainQuery, FlatHeightmapHasUpNormals) {
  const fs::path path = tempDir() / "flat.png";
  writeGrey8Png(path, 9, 9, std::vector<std::uint8_t>(81, 128));
  TerrainSettings s;
  s.heightmap = path.string();
  s.size = 80.0;
  s.heightScale = 100.0;
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_DOUBLE_EQ(t->spacing(), 10.0);
  const glm::vec3 n = t->normalAt(33.0, 47.0);
  EXPECT_NEAR(n.y, 1.0f, 1e-6f);
  EXPECT_NEAR(t->heightAt(33.0, 47.0), 128.0 * 257.0 / 65535.0 * 100.0, 1e-3);
}

TEST(TerrainPng, Loads8BitGrey) {
  const fs::path path = tempDir() / "ramp8.png";
  std::vector<std::uint8_t> v(17 * 9);
  for (int z = 0; z < 9; ++z)
    for (int x = 0; x < 17; ++x) v[std::size_t(z) * 17 + x] = std::uint8_t(x * 15);
  writeGrey8Png(path, 17, 9, v);
  TerrainSettings s;
  s.heightmap = path.string();
  s.size = 160.0;
  s.heightScale = 255.0;
  s.origin = {0.0, -10.0, 0.0};
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->cellsX(), 16);
  EXPECT_EQ(t->cellsZ(), 8);
  EXPECT_DOUBLE_EQ(t->spacing(), 10.0);
  // Pixel value v maps to v / 255 of the height scale.
  EXPECT_NEAR(t->heightAt(50.0, 40.0), -10.0 + 75.0, 1e-3);
  EXPECT_NEAR(t->heightAt(160.0, 80.0), -10.0 + 240.0, 1e-3);
  EXPECT_NEAR(t->heightRange().max, 240.0f, 1e-3f);
  // A ramp is linear: every level's mesh is exact.
  for (int level = 0; level < t->levelCount(); ++level) EXPECT_LT(t->geometricError(level), 1e-3f);
}

TEST(TerrainPng, Loads16BitGreyAtFullPrecision) {
  const fs::path path = tempDir() / "ramp16.png";
  const int w = 65, h = 33;
  std::vector<std::uint16_t> v(std::size_t(w) * h);
  for (int z = 0; z < h; ++z)
    for (int x = 0; x < w; ++x) v[std::size_t(z) * w + x] = std::uint16_t(x * 1000 + z * 7 + 1);
  writeGrey16Png(path, w, h, v);
  TerrainSettings s;
  s.heightmap = path.string();
  s.size = 64.0;
  s.heightScale = 65535.0;  // one metre per grey step
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->cellsX(), 64);
  EXPECT_EQ(t->cellsZ(), 32);
  // Steps of 7 between rows would be lost at 8 bits.
  EXPECT_NEAR(t->heightAt(10.0, 3.0), 10.0 * 1000 + 3 * 7 + 1, 1e-2);
  EXPECT_NEAR(t->heightAt(10.0, 4.0) - t->heightAt(10.0, 3.0), 7.0, 1e-2);
}

TEST(TerrainBadInput, ErrorsNameTheFileOrField) {
  auto expectError = [](const TerrainSettings& s, const std::string& needle) {
    auto t = Terrain::create(s);
    ASSERT_FALSE(t.ok()) << "expected an error mentioning " << needle;
    EXPECT_NE(t.error().message.find(needle), std::string::npos) << t.error().message;
  };
  TerrainSettings s;
  s.heightmap = (tempDir() / "does_not_exist.png").string();
  expectError(s, "does_not_exist.png");

  const fs::path text = tempDir() / "not_a_png.png";
  std::ofstream(text) << "this is not an image";
  s.heightmap = text.string();
  expectError(s, "not_a_png.png");

  const fs::path tiny = tempDir() / "one_pixel.png";
  writeGrey8Png(tiny, 1, 1, {7});
  s.heightmap = tiny.string();
  expectError(s, "one_pixel.png");

  const fs::path empty = tempDir() / "empty.png";
  std::ofstream(empty).close();
  s.heightmap = empty.string();
  expectError(s, "empty.png");

  TerrainSettings n = test::noiseSettings(1024.0, 100.0);
  n.size = 0.0;
  expectError(n, "size");
  n.size = -5.0;
  expectError(n, "size");
  n = test::noiseSettings(1024.0, 100.0);
  n.spacing = 0.0;
  expectError(n, "spacing");
  n.spacing = std::nan("");
  expectError(n, "spacing");
  n = test::noiseSettings(1024.0, -1.0);
  expectError(n, "heightScale");
  n = test::noiseSettings(100000.0, 100.0);  // 100,000 cells a side
  expectError(n, "65536");
  n = test::noiseSettings(1024.0, 100.0);
  n.origin.x = INFINITY;
  expectError(n, "origin");
  n = test::noiseSettings(1024.0, 100.0);
  n.pageCacheBytes = 1000;
  expectError(n, "pageCacheBytes");
  // A size error on a heightmap names the file too.
  s.heightmap = (tempDir() / "ramp8.png").string();
  s.size = -1.0;
  expectError(s, "ramp8.png: size");
}

TEST(TerrainPaging, CacheEvictsWithinItsBudgetAndRemakesPagesExactly) {
  TerrainSettings s = test::noiseSettings(2048.0, 300.0);
  s.pageCacheBytes = 40 * kPageBytes;
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  const double before = t->heightAt(17.3, 1999.1);
  const glm::vec3 normalBefore = t->normalAt(17.3, 1999.1);
  for (int nz = 0; nz < 32; ++nz)
    for (int nx = 0; nx < 32; nx += 4) {
      (void)t->page({0, nx, nz});
      ASSERT_LE(t->cacheStats().bytes, s.pageCacheBytes);
    }
  EXPECT_GT(t->cacheStats().evictions, 0u);
  EXPECT_LE(t->cacheStats().peakBytes, s.pageCacheBytes);
  EXPECT_EQ(t->heightAt(17.3, 1999.1), before);
  EXPECT_EQ(t->normalAt(17.3, 1999.1), normalBefore);
}

// Each page's four patch ranges are the least and greatest of the samples the
// patch's grid reads, straight from the source (indices clamped at the field's
// edge), on pages of three levels, the field's edges included.
TEST(TerrainPaging, PatchRangesAreTheExtremesOfThePatchesSamples) {
  auto t = Terrain::create(test::noiseSettings(1024.0, 300.0));
  ASSERT_TRUE(t.ok()) << t.error().message;
  for (const PageKey key : {PageKey{0, 0, 0}, PageKey{0, 3, 5}, PageKey{1, 2, 1}, PageKey{2, 1, 1}, PageKey{0, 15, 15}}) {
    const auto page = t->page(key);
    const int s = Terrain::stride(key.level);
    for (int q = 0; q < 4; ++q) {
      float lo = 1e30f, hi = -1e30f;
      for (int j = 0; j <= kPatchQuads; ++j)
        for (int i = 0; i <= kPatchQuads; ++i) {
          const float h = t->sample((key.nx * kNodeQuads + (q & 1) * kPatchQuads + i) * s,
                                    (key.nz * kNodeQuads + (q >> 1) * kPatchQuads + j) * s);
          lo = std::min(lo, h);
          hi = std::max(hi, h);
        }
      EXPECT_EQ(page->patchRanges[size_t(q)].min, lo) << key.level << " " << key.nx << " " << key.nz << " " << q;
      EXPECT_EQ(page->patchRanges[size_t(q)].max, hi);
      EXPECT_LT(lo, hi);
    }
  }
}

// The 16 km x 16 km field at 1 m spacing (16385^2 samples, 1 GiB as floats) flown
// across at low altitude: pages are made as the selection needs them, and the cache
// never holds more than the stated budget.
TEST(TerrainPaging, FlyAcross16KmStaysWithinTheBudget) {
  TerrainSettings s = test::noiseSettings(16384.0, 1500.0);
  auto t = Terrain::create(s);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->cellsX(), 16384);
  EXPECT_EQ(t->cacheStats().budgetBytes, kDefaultPageCacheBytes);
  const double fullField = 16385.0 * 16385.0 * sizeof(float);
  EXPECT_GT(fullField, 4.0 * double(kDefaultPageCacheBytes));
  std::size_t pagesTouched = 0;
  const int steps = 24;
  for (int i = 0; i <= steps; ++i) {
    const double f = double(i) / steps;
    const glm::dvec3 ground(300.0 + f * 15700.0, 0.0, 500.0 + f * 15000.0);
    const double y = t->heightAt(ground.x, ground.z) + 30.0;
    const glm::dvec3 eye(ground.x, y, ground.z);
    const LodCamera camera = test::makeCamera(eye, eye + glm::dvec3(1.0, -0.15, 1.0));
    const LodSelection selection = selectLod(*t, camera, 2.0);
    ASSERT_FALSE(selection.patches.empty());
    for (const LodPatch& p : selection.patches) {
      (void)t->page(p.node);
      ++pagesTouched;
      ASSERT_LE(t->cacheStats().bytes, kDefaultPageCacheBytes);
    }
  }
  EXPECT_LE(t->cacheStats().peakBytes, kDefaultPageCacheBytes);
  EXPECT_GT(t->cacheStats().misses, 100u);
  std::printf("16 km fly-through: %zu page requests, %llu made, peak %.1f MiB of %.0f MiB\n", pagesTouched,
              static_cast<unsigned long long>(t->cacheStats().misses),
              double(t->cacheStats().peakBytes) / (1 << 20), double(kDefaultPageCacheBytes) / (1 << 20));
}
