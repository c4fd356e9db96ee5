// The rasterizer's PBR ambient against the path tracer, which integrates the
// environment exactly (BRDF * L * cos over the hemisphere): a rough dielectric and a
// metal sphere under the gradient sky, no lights, so the ambient is all the light
// there is. Each sphere is drawn alone: beside each other, the metal one mirrors the
// other, which no ambient term models (the path tracer's inter-reflection, not the
// environment). The split-sum IBL must come much closer than the hemisphere ambient.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "asset/scene_file.h"
#include "core/image.h"
#include "rasterized.h"
#include "raytrace/scene_builder.h"

using namespace engine;

namespace {

constexpr int kIblWidth = 240, kIblHeight = 160;

constexpr const char* kScene = R"({
  "camera": {"position": [0, 1, 6], "target": [0, 1, 0], "fovy": 40},
  "sky": {"zenith": [0.15, 0.35, 1.0], "horizon": [0.9, 0.85, 0.75], "ground": [0.3, 0.25, 0.2]},
  "materials": {"rough": {"color": [0.8, 0.35, 0.2], "roughness": 0.7},
                "metal": {"color": [0.95, 0.8, 0.5], "metallic": 1, "roughness": 0.3}},
  "primitives": [{"type": "sphere", "center": [-1.3, 1, 0], "radius": 1, "material": "rough"},
                 {"type": "sphere", "center": [1.3, 1, 0], "radius": 1, "material": "metal"}],
  "render": {"ibl_size": 128}
})";

Image rasterized(const SceneDesc& scene, Ambient ambient) {
  SceneRenderOptions options;
  options.ambientOverride = ambient;
  return test::rasterizedWith(scene, options, kIblWidth, kIblHeight);
}

Image pathTraced(const SceneDesc& scene) {
  rt::RenderSettings settings;
  settings.method = rt::Method::Path;
  settings.width = kIblWidth;
  settings.height = kIblHeight;
  settings.samplesPerPixel = 256;
  settings.maxDepth = 16;
  auto traced = rt::raytraceScene(scene, 0.0, settings);
  EXPECT_TRUE(traced.ok()) << traced.error().message;
  return traced.ok() ? traced->image : Image{};
}

// Pixels whose whole footprint lies on a sphere: the centre ray and the four
// corner rays all hit (silhouettes are antialiased differently by the two).
std::vector<bool> sphereInterior(const SceneDesc& scene) {
  const CameraDesc& c = scene.camera;
  const double yScale = std::tan(glm::radians(c.fovyDegrees) * 0.5), xScale = yScale * kIblWidth / kIblHeight;
  const glm::dvec3 right = c.right(), up = glm::normalize(glm::cross(right, c.forward));
  auto hits = [&](double x, double y) {
    const double px = (2.0 * x / kIblWidth - 1.0) * xScale, py = -(2.0 * y / kIblHeight - 1.0) * yScale;
    const glm::dvec3 d = glm::normalize(right * px + up * py + c.forward);
    for (const PrimitiveDesc& p : scene.primitives) {
      const glm::dvec3 oc = c.position - p.center;
      const double b = glm::dot(oc, d);
      if (b * b - (glm::dot(oc, oc) - p.radius * p.radius) > 0.0) return true;
    }
    return false;
  };
  std::vector<bool> mask(size_t(kIblWidth * kIblHeight));
  for (int y = 0; y < kIblHeight; ++y)
    for (int x = 0; x < kIblWidth; ++x)
      mask[size_t(y * kIblWidth + x)] = hits(x + 0.5, y + 0.5) && hits(x - 0.5, y - 0.5) && hits(x + 1.5, y - 0.5) &&
                                     hits(x - 0.5, y + 1.5) && hits(x + 1.5, y + 1.5);
  return mask;
}

struct MaskedError {
  double mean = 0.0, psnr = 0.0;
};

// Over the RGB channels of the masked pixels, in 8-bit display values.
MaskedError errorInside(const Image& a, const Image& b, const std::vector<bool>& mask) {
  double sum = 0.0, squares = 0.0;
  int count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    for (size_t c = 0; c < 3; ++c) {
      const double d = double(a.pixels[i * 4 + c]) - double(b.pixels[i * 4 + c]);
      sum += std::abs(d);
      squares += d * d;
    }
    count += 3;
  }
  MaskedError e;
  e.mean = sum / count;
  e.psnr = 10.0 * std::log10(255.0 * 255.0 / std::max(squares / count, 1e-12));
  return e;
}

// One sphere of kScene alone (the other removed).
SceneDesc alone(const SceneDesc& scene, size_t sphere) {
  SceneDesc one = scene;
  one.primitives = {scene.primitives[sphere]};
  return one;
}

struct Errors {
  MaskedError hemisphere, sh, ibl;
};

Errors errorsOf(const SceneDesc& scene, const char* name) {
  const Image traced = pathTraced(scene);
  const Image hemisphere = rasterized(scene, Ambient::Hemisphere), sh = rasterized(scene, Ambient::Sh),
              ibl = rasterized(scene, Ambient::Ibl);
  Errors e;
  if (traced.empty() || hemisphere.empty() || sh.empty() || ibl.empty()) return e;
  const auto mask = sphereInterior(scene);
  e = {errorInside(traced, hemisphere, mask), errorInside(traced, sh, mask), errorInside(traced, ibl, mask)};
  std::printf("%s sphere against the path tracer (256 spp), mean abs error (8-bit) and PSNR: hemisphere %.2f "
              "%.2f dB, sh %.2f %.2f dB, ibl %.2f %.2f dB\n",
              name, e.hemisphere.mean, e.hemisphere.psnr, e.sh.mean, e.sh.psnr, e.ibl.mean, e.ibl.psnr);
  if (std::getenv("ENGINE_WRITE_DIFFS")) {
    const std::string prefix = std::string("ibl_vs_pathtrace_") + name;
    (void)writePng(prefix + "_traced.png", traced);
    (void)writePng(prefix + "_hemisphere.png", hemisphere);
    (void)writePng(prefix + "_sh.png", sh);
    (void)writePng(prefix + "_ibl.png", ibl);
  }
  return e;
}

}  // namespace

TEST(IblVsPathTrace, IblApproachesThePathTracedEnvironmentLight) {
  auto scene = parseScene(kScene, "ibl_spheres.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Errors rough = errorsOf(alone(*scene, 0), "rough"), metal = errorsOf(alone(*scene, 1), "metal");
  // Measured (llvmpipe, 240x160, 256 spp), mean abs error in 8-bit display values
  // and PSNR over the spheres' interiors: rough sphere hemisphere 74.2 (10.6 dB), sh
  // 1.41 (42.9 dB), ibl 1.40 (43.0 dB); metal sphere hemisphere 128.2 (5.8 dB), sh
  // 11.6 (24.9 dB), ibl 1.25 (43.2 dB). The hemisphere ambient is a dimmed guess at
  // the sky (scene_desc.h), far too dark; SH is as good as IBL on the rough
  // dielectric, whose light is nearly all diffuse, but blurs the metal's reflection
  // of the horizon into a Lambert lobe. What IBL leaves is the split sum's
  // assumptions (N = V = R in the prefilter, the lobe's shape at grazing views),
  // the tessellated sphere's normals and the path tracer's noise. The limits leave
  // 1.6x room for another driver's rounding and another seed. Measured failures:
  // the table's scale and bias swapped (ibl 58.2 rough, 17.0 metal), the diffuse
  // without its 1 / pi (60.4 rough), the roughest level for every surface (11.9
  // metal), the unfiltered environment for every surface (2.11 metal, just past
  // its limit: this smooth sky tells a glossy lobe from a mirror only at the
  // horizon; tests/render/ibl_test.cpp checks the convolution itself).
  EXPECT_LT(rough.ibl.mean, 2.3);
  EXPECT_LT(metal.ibl.mean, 2.0);
  EXPECT_GT(rough.ibl.psnr, 38.0);
  EXPECT_GT(metal.ibl.psnr, 38.0);
  EXPECT_LT(rough.ibl.mean, 0.1 * rough.hemisphere.mean);
  EXPECT_LT(metal.ibl.mean, 0.1 * metal.hemisphere.mean);
  EXPECT_LT(metal.ibl.mean, 0.5 * metal.sh.mean);
}
