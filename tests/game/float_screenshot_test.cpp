// Float screenshots (--screenshot F.exr / F.pfm): the linear radiance each renderer
// hands the runner is the image its PNG encodes. The rasterizer's is its HDR target
// before the post pass, the CPU tracer's window the mean of its passes so far; each,
// tone mapped and encoded the tracers' way (raytrace/tone_map.h), gives the frame's
// bytes of the same run.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "../support/gl_test.h"
#include "../support/radiance_file.h"
#include "app/runner.h"
#include "asset/scene_file.h"
#include "core/float_image_io.h"
#include "progressive_trace.h"
#include "raytrace/scene_builder.h"
#include "raytrace/tone_map.h"
#include "scene_game.h"

using namespace engine;
using engine::test::GlTest;
using engine::test::ScratchFolder;

namespace {

struct LevelsApart {
  int largest = 0;
  std::size_t differing = 0, channels = 0;
};

// `linear` through the tracers' tone map and curve against `encoded`, channel by channel.
LevelsApart encodedAgainst(const FloatImage& linear, const Image& encoded, const RenderDesc& render) {
  LevelsApart d;
  EXPECT_EQ(linear.width, encoded.width);
  EXPECT_EQ(linear.height, encoded.height);
  if (linear.width != encoded.width || linear.height != encoded.height) return d;
  for (int y = 0; y < linear.height; ++y) {
    for (int x = 0; x < linear.width; ++x) {
      const glm::vec3 c = rt::toneMap(linear.at(x, y), render);
      for (int k = 0; k < 3; ++k) {
        const int apart = std::abs(int(rt::encodeChannel(c[k], render.output)) - int(encoded.at(x, y)[k]));
        d.largest = std::max(d.largest, apart);
        d.differing += apart != 0;
        ++d.channels;
      }
    }
  }
  return d;
}

SceneDesc loadShippedScene(const std::string& name) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + name);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene ? *scene : SceneDesc{};
}

// A headless run of the demo's game writing `screenshot`; its PNG frame in `frame`.
Status runScene(const SceneDesc& scene, bool hdrTarget, const std::string& screenshot, Image& frame) {
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.hdrTarget = hdrTarget;
  demo::SceneGame game(scene, options);
  RunOptions run;
  run.width = 96;
  run.height = 64;
  run.time = 0.5;
  run.screenshot = screenshot;
  run.debugGl = true;
  return runHeadless(Backend::Egl, game, run, &frame);
}

}  // namespace

// The room (classic shading, no tone map, gamma 2.2) and the material scene (PBR,
// ACES, sRGB). The file holds the half floats the post pass read, so the only
// difference left is arithmetic: the post pass evaluates ACES and gamma 2.2's pow()
// in GLSL, the tracers in C++, and a value on a level's edge may round either way.
// Measured: none apart (llvmpipe rounds as the CPU). A level and one channel in 50
// allow another GPU's rounding; an exposure, tone map or curve applied twice or not
// at all moves most channels by many levels.
TEST(FloatScreenshot, TheRasterizersLinearFrameEncodesToItsPng) {
  ScratchFolder folder;
  for (const char* name : {"cornell.json", "materials.json"}) {
    for (const char* file : {"frame.exr", "frame.pfm"}) {
      SCOPED_TRACE(std::string(name) + " " + file);
      const SceneDesc scene = loadShippedScene(name);
      const std::string path = (folder / file).string();
      Image frame;
      const Status run = runScene(scene, true, path, frame);
      ASSERT_TRUE(run.ok()) << run.error().message;
      auto linear = readFloatImage(path);
      ASSERT_TRUE(linear.ok()) << linear.error().message;
      const LevelsApart d = encodedAgainst(*linear, frame, scene.render);
      std::printf("%s %s: %zu of %zu channels apart, by %d at most\n", name, file, d.differing, d.channels, d.largest);
      EXPECT_LE(d.largest, 1);
      EXPECT_LE(d.differing, d.channels / 50);
    }
  }
}

// Direct output has no HDR target: the run fails naming the file rather than write
// something else (demo and viewer keep the target when the name asks for floats).
TEST(FloatScreenshot, DirectOutputHasNoLinearFrame) {
  ScratchFolder folder;
  // A sky and nothing that needs the HDR target.
  auto scene = parseScene("{}", std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/empty.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const std::string path = (folder / "direct.exr").string();
  Image frame;
  const Status run = runScene(*scene, false, path, frame);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().message.rfind(path + ": the rasterizer drew this frame without its HDR target", 0), 0u)
      << run.error().message;
  EXPECT_FALSE(std::filesystem::exists(path));
  ASSERT_TRUE(runScene(*scene, true, path, frame).ok());
  EXPECT_TRUE(readFloatImage(path).ok());
}

class FloatScreenshotTrace : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(FloatScreenshotTrace);

// The CPU tracer's window: once every pass is in, the linear image encodes to the
// bytes the window shows (the same sum over the same count), and is the offscreen
// render's framebuffer up to the order of the sums (float, a few ulps).
TEST_P(FloatScreenshotTrace, TheWindowsPathTraceIsTheMeanOfItsPasses) {
  const SceneDesc desc = loadShippedScene("cornell.json");
  rt::RenderSettings settings;
  settings.method = rt::Method::Path;
  settings.width = 40;
  settings.height = 24;
  settings.samplesPerPixel = 3;
  auto scene = rt::buildRtScene(desc, 0.0, settings.height);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  auto trace = demo::ProgressiveTrace::start(std::make_unique<rt::RtScene>(std::move(*scene)), settings, false);
  ASSERT_TRUE(trace.ok()) << trace.error().message;
  while ((*trace)->passesDone() < (*trace)->passes()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const FloatImage linear = (*trace)->linearSnapshot();
  const LevelsApart d = encodedAgainst(linear, (*trace)->snapshot(), desc.render);
  EXPECT_EQ(d.largest, 0);
  auto again = rt::buildRtScene(desc, 0.0, settings.height);
  ASSERT_TRUE(again.ok()) << again.error().message;
  const FloatImage offscreen = rt::toFloatImage(rt::Integrator(*again, settings).render().image);
  ASSERT_EQ(linear.rgb.size(), offscreen.rgb.size());
  for (std::size_t i = 0; i < linear.rgb.size(); ++i)
    ASSERT_NEAR(linear.rgb[i], offscreen.rgb[i], 1e-5f * std::max(1.0f, std::abs(offscreen.rgb[i]))) << i;
}
