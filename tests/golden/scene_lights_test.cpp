// Lights beyond the course's sun and point lights, through both renderers from the
// scene's environment (scene/environment.h): a second sun, which the rasterizer
// draws as an unshadowed directional light in its light array, spots with a soft and
// a sharp cone, and a model's own
// KHR_lights_punctual lamps in a scene file, which neither renderer drew before the
// environment placed them.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "asset/scene_file.h"
#include "core/image.h"
#include "raytrace/scene_builder.h"
#include "../support/traced.h"
#include "rasterized.h"

namespace engine {
namespace {

constexpr int kLightsWidth = 256, kLightsHeight = 192;

Image tracedAtPixelCentres(const SceneDesc& scene) {
  return test::tracedAtPixelCentres(scene, kLightsWidth, kLightsHeight);
}

Image rasterizedAt(const SceneDesc& scene) {
  return test::rasterizedWith(scene, SceneRenderOptions{}, kLightsWidth, kLightsHeight);
}

double meanLevel(const Image& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i] + image.pixels[i + 1] + image.pixels[i + 2];
  return sum / (3.0 * double(image.pixels.size() / 4));
}

// A grey sphere on a grey floor, classic shading without shadows (the tracer's hard
// shadows and the rasterizer's map differ at their edges, which is not what is
// tested here), lit by `lights` (a JSON array's items) and seen from `eye`.
Result<SceneDesc> greySphereOnAFloor(const std::string& lights, const std::string& eye, const std::string& name) {
  return parseScene(R"({"camera": {"position": )" + eye + R"(, "target": [0, 0.6, 0], "fovy": 45},
    "lights": [)" + lights + R"(],
    "materials": {"grey": {"color": [0.7, 0.7, 0.7], "specular": 0.3, "shininess": 24}},
    "primitives": [{"type": "sphere", "center": [0, 0.8, 0], "radius": 0.8, "material": "grey"},
                   {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "extent": 20, "material": "grey"}],
    "sky": {"enabled": false, "background": [0.05, 0.05, 0.05]},
    "ambient": 0.1,
    "render": {"shading": "classic", "msaa": 1}})",
                    name);
}

// The rasterizer's frame of `lit` within 1 level (mean) of the Whitted tracer's, and
// at least 4 levels from its frame of `without` (the lights under test removed).
void expectBothRenderersLitAlike(Result<SceneDesc> lit, Result<SceneDesc> without, const char* what) {
  ASSERT_TRUE(lit.ok()) << lit.error().message;
  ASSERT_TRUE(without.ok()) << without.error().message;
  const Image raster = rasterizedAt(*lit);
  const Image traced = tracedAtPixelCentres(*lit);
  const Image rasterWithout = rasterizedAt(*without);
  ASSERT_FALSE(raster.empty() || traced.empty() || rasterWithout.empty());
  auto agree = compareImages(raster, traced, 16);
  auto moved = compareImages(raster, rasterWithout, 16);
  ASSERT_TRUE(agree.ok() && moved.ok());
  std::printf("%s: raster vs traced mean %.3f, PSNR %.2f dB; the lights move the raster by %.3f\n", what,
              agree->meanAbs, agree->psnr, moved->meanAbs);
  EXPECT_LT(agree->meanAbs, 1.0);
  EXPECT_GT(moved->meanAbs, 4.0);
  if (::testing::Test::HasFailure() || std::getenv("ENGINE_WRITE_DIFFS")) {
    (void)writePng(std::string("scene_lights_") + what + "_traced.png", traced);
    (void)writePng(std::string("scene_lights_") + what + "_raster.png", raster);
  }
}

// A white sun from above-front and a red one from the right. Measured (EGL,
// llvmpipe, 2026-12-07): the two renderers' frames differ by a mean of 0.008 levels
// (PSNR 56.9 dB); the red sun moves the rasterized frame by a mean of 8.1 levels.
TEST(RasterVsRaytrace, ASecondSunLightsBothRenderersAlike) {
  const std::string white = R"({"type": "sun", "direction": [0, 1, 1], "color": [1, 1, 1], "intensity": 0.6, "shadows": false})";
  const std::string red = R"({"type": "sun", "direction": [1, 0.5, 0], "color": [1, 0.2, 0.1], "intensity": 0.8, "shadows": false})";
  expectBothRenderersLitAlike(greySphereOnAFloor(white + ", " + red, "[0, 1.5, 5]", "two_suns.json"),
                              greySphereOnAFloor(white, "[0, 1.5, 5]", "one_sun.json"), "two_suns");
}

// A warm spot straight down with a soft edge (cones 15 and 35 degrees, 1/d^2) and a
// blue one aimed past the sphere from the left with a sharp one (20 and 20).
// Measured (EGL, llvmpipe, 2026-12-07): the frames differ by a mean of 0.003 levels
// (PSNR 69.2 dB); the spots move the rasterized frame by a mean of 26.8 levels.
TEST(RasterVsRaytrace, SpotLightsLightBothRenderersAlike) {
  const std::string spots = R"({"type": "spot", "position": [0.6, 3, 0.8], "direction": [-0.2, -1, -0.3],
        "inner_cone": 15, "outer_cone": 35, "falloff": true, "intensity": 9, "color": [1, 0.85, 0.6], "shadows": false},
      {"type": "spot", "position": [-3, 1.5, 0.5], "direction": [1, -0.25, -0.2], "inner_cone": 20, "outer_cone": 20,
        "intensity": 0.8, "color": [0.5, 0.7, 1], "shadows": false})";
  expectBothRenderersLitAlike(greySphereOnAFloor(spots, "[0, 2.5, 5]", "spots.json"),
                              greySphereOnAFloor("", "[0, 2.5, 5]", "no_spots.json"), "spots");
}

const std::string kLamp =
    std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf";

// The Khronos lamp on a grey floor, in a scene file with no lights of its own: the
// lamp's five point lights (15 to 180 cd) are all that lights it beyond a dim
// ambient. `lamp` false: the floor alone, the ambient's level.
Result<SceneDesc> lampOnAFloor(bool lamp) {
  const std::string models = lamp ? R"("models": [{"path": ")" + kLamp + R"("}],)" : "";
  return parseScene(R"({"camera": {"position": [0, 1.2, 4.5], "target": [0, 0.4, 0], "fovy": 45},
    )" + models + R"(
    "materials": {"floor": {"color": [0.6, 0.6, 0.6], "metallic": 0, "roughness": 0.8}},
    "primitives": [{"type": "plane", "point": [0, -0.78, 0], "normal": [0, 1, 0], "extent": 20, "material": "floor"}],
    "sky": {"enabled": false, "background": [0.02, 0.02, 0.02]},
    "ambient": 0.5,
    "render": {"shading": "pbr", "ambient": "hemisphere", "exposure": 0.08, "msaa": 1}})",
                    "lamp.json");
}

// Measured (EGL, llvmpipe, 2026-12-07): the two renderers' frames differ by a mean
// of 0.70 levels (PSNR 31.3 dB: the lamp's glass and the floor's highlight); the
// lamp's lights raise the frame's mean level from 19.4 (the floor under the ambient
// alone, as both renderers drew this scene before its environment took the model's
// lights) to 106.4. Limits: a mean difference of 1.5 levels, and the lights adding
// at least 40 levels in each renderer, under half of what they add.
TEST(RasterVsRaytrace, AModelsOwnLampsLightBothRenderers) {
  if (!std::filesystem::exists(kLamp)) GTEST_SKIP() << kLamp << " not found";
  auto scene = lampOnAFloor(true);
  auto floor = lampOnAFloor(false);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_TRUE(floor.ok()) << floor.error().message;
  const Image raster = rasterizedAt(*scene);
  const Image traced = tracedAtPixelCentres(*scene);
  const Image unlit = rasterizedAt(*floor);
  ASSERT_FALSE(raster.empty() || traced.empty() || unlit.empty());
  auto agree = compareImages(raster, traced, 16);
  ASSERT_TRUE(agree.ok());
  std::printf("lamp: raster vs traced mean %.3f, PSNR %.2f dB; mean levels raster %.2f, traced %.2f, floor alone %.2f\n",
              agree->meanAbs, agree->psnr, meanLevel(raster), meanLevel(traced), meanLevel(unlit));
  EXPECT_LT(agree->meanAbs, 1.5);
  EXPECT_GT(meanLevel(raster) - meanLevel(unlit), 40.0);
  EXPECT_GT(meanLevel(traced) - meanLevel(unlit), 40.0);
  if (::testing::Test::HasFailure() || std::getenv("ENGINE_WRITE_DIFFS")) {
    (void)writePng("scene_lights_lamp_traced.png", traced);
    (void)writePng("scene_lights_lamp_raster.png", raster);
  }
}

}  // namespace
}  // namespace engine
