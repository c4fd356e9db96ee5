// The LOD target's contract, measured: over random cameras (over the field and
// beyond it, near the ground and high above, looking anywhere from steeply down
// to above the horizon, narrow and wide fields of view) on fields of several
// roughnesses, the drawn surface's largest screen-space error against the full-
// resolution grid (bench/terrain_error.h, micro_bench's measure) is within the
// target it was selected for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "../../bench/terrain_error.h"
#include "core/image.h"
#include "terrain/lod.h"
#include "terrain/terrain.h"
#include "terrain_support.h"

using namespace engine;
using namespace engine::terrain;

namespace {

// splitmix64: the same cameras on every platform (std's distributions are not).
struct SweepRandom {
  std::uint64_t state;
  double uniform(double lo, double hi) {
    std::uint64_t x = (state += 0x9E3779B97F4A7C15ull);
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    x ^= x >> 31;
    return lo + (hi - lo) * double(x >> 11) * (1.0 / 9007199254740992.0);
  }
};

struct SweepField {
  std::string name;
  TerrainSettings settings;
};

// A smooth but busy 8-bit heightmap whose size is no multiple of a node, so nodes
// hang over its edges: the exact level-wide errors and the clamped grid.
std::string raggedHeightmap() {
  Image image(401, 277);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.at(x, y);
      const double v = std::sin(x * 0.043) * std::cos(y * 0.061) + 0.3 * std::sin((x + 2 * y) * 0.17);
      p[0] = p[1] = p[2] = std::uint8_t(128 + 95 * v);
      p[3] = 255;
    }
  const auto path = std::filesystem::temp_directory_path() / "engine_terrain_sweep.png";
  EXPECT_TRUE(writePng(path.string(), image).ok());
  return path.string();
}

std::vector<SweepField> sweepFields() {
  std::vector<SweepField> fields;
  auto noise = [&](const char* name, std::uint32_t seed, double size, double spacing, double height, double feature) {
    TerrainSettings s = test::noiseSettings(size, height, {-3.0e5, 120.0, 7.0e5});
    s.seed = seed;
    s.spacing = spacing;
    s.featureSize = feature;
    fields.push_back({name, s});
  };
  noise("rough", 11, 1024.0, 1.0, 400.0, 256.0);
  noise("gentle", 5, 1536.0, 1.0, 150.0, 0.0);
  noise("2 m spacing", 3, 2048.0, 2.0, 500.0, 0.0);
  TerrainSettings png;
  png.heightmap = raggedHeightmap();
  png.size = 1600.0;
  png.heightScale = 260.0;
  fields.push_back({"ragged heightmap", png});
  return fields;
}

struct SweepView {
  LodCamera camera;
  double pixels = 1.0;
  std::string description;
};

SweepView randomView(const Terrain& t, SweepRandom& random) {
  const double size = std::max(t.cellsX(), t.cellsZ()) * t.spacing();
  const glm::dvec3 o = t.origin();
  const double x = o.x + random.uniform(-0.2, 1.2) * size, z = o.z + random.uniform(-0.2, 1.2) * size;
  // Log-uniform heights above the ground: 1.5 m to 600 m.
  const double above = 1.5 * std::exp(random.uniform(0.0, std::log(400.0)));
  const glm::dvec3 eye(x, t.heightAt(x, z) + above, z);
  const double yaw = random.uniform(0.0, 6.283185307179586);
  const double pitch = glm::radians(random.uniform(-70.0, 15.0));
  const glm::dvec3 look(std::cos(yaw) * std::cos(pitch), std::sin(pitch), std::sin(yaw) * std::cos(pitch));
  const int heights[] = {360, 720, 1080};
  const int height = heights[int(random.uniform(0.0, 2.999))];
  const double fov = random.uniform(35.0, 90.0);
  const double targets[] = {0.5, 1.0, 2.0, 3.0};
  SweepView v;
  v.pixels = targets[int(random.uniform(0.0, 3.999))];
  v.camera = test::makeCamera(eye, eye + look, height * 16 / 9, height, fov);
  v.camera.cull = random.uniform(0.0, 1.0) < 0.75;  // unculled: every direction at once
  std::ostringstream d;
  d << "eye (" << x - o.x << ", " << above << " m up, " << z - o.z << "), yaw " << yaw << ", pitch "
    << glm::degrees(pitch) << ", fov " << fov << ", " << height << " px high, cull " << v.camera.cull << ", target "
    << v.pixels << " px";
  v.description = d.str();
  return v;
}

}  // namespace

TEST(LodError, MeasuredScreenErrorIsWithinTheTargetFromRandomCameras) {
  constexpr int kViewsPerField = 16;
  SweepRandom random{0x5EEDu};
  double worstRatio = 0.0;
  for (const SweepField& field : sweepFields()) {
    auto t = Terrain::create(field.settings);
    ASSERT_TRUE(t.ok()) << field.name << ": " << t.error().message;
    for (int i = 0; i < kViewsPerField; ++i) {
      const SweepView v = randomView(*t, random);
      const LodSelection s = test::settledSelection(*t, v.camera, v.pixels);
      const double measured = terrain::bench::measuredScreenError(*t, s, v.camera);
      EXPECT_LE(measured, v.pixels) << field.name << ": " << v.description << ", " << s.patches.size() << " patches";
      worstRatio = std::max(worstRatio, measured / v.pixels);
    }
  }
  RecordProperty("worst_measured_over_target", std::to_string(worstRatio));
  // The views are demanding enough to come near the target somewhere: a
  // selection that wasted most of it would not show here otherwise.
  EXPECT_GT(worstRatio, 0.5);
}
