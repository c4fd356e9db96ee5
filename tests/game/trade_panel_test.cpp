// The demo's trade panel logic (game/demo/scene_game.h), without clicking: a knob
// rebuilds the renderer over the same loaded scene, a scene that fails to load
// leaves the current one in place with its error for the panel, and the frame's
// passes report GPU times.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../support/gl_test.h"
#include "../support/radiance_file.h"
#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "reference_view.h"
#include "render/render_target.h"
#include "scene/scene.h"
#include "scene_game.h"

using namespace engine;
using engine::test::GlTest;
using demo::ProgressiveTrace;

namespace {

class TradePanel : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(TradePanel);

const std::string kScenes = std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/";
// How near the noise estimate comes to the measured error. Measured: 27.64 dB
// estimated, 27.08 dB actual (0.56 dB; the tone curve and 8-bit clipping make the
// halves' errors not exactly additive, and the 512-spp image adds its own ~0.1 dB).
// Forgetting that each half has twice the variance would be off by 6 dB.
constexpr double kNoiseEstimateDb = 1.5;

std::unique_ptr<demo::SceneGame> startGame(const std::string& file) {
  auto desc = loadSceneFile(kScenes + file);
  EXPECT_TRUE(desc.ok()) << desc.error().message;
  if (!desc) return nullptr;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.iblSizeOverride = 16;
  auto game = std::make_unique<demo::SceneGame>(*desc, options, true);
  const Status started = game->init();
  EXPECT_TRUE(started.ok()) << started.error().message;
  return started ? std::move(game) : nullptr;
}

Status frame(demo::SceneGame& game, RenderTarget& target, double time) {
  target.bind();
  game.update(time, 1.0 / 60.0);
  return game.render({time, target.width(), target.height()});
}

// Waits for the reference to finish every pass (two minutes at most).
bool finish(demo::ReferenceView& view) {
  const auto start = std::chrono::steady_clock::now();
  while (view.trace()->passesDone() < view.trace()->passes()) {
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(120)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

}  // namespace

TEST_P(TradePanel, AKnobRebuildsTheRendererOverTheSameScene) {
  auto game = startGame("demo.json");
  ASSERT_TRUE(game);
  auto target = RenderTarget::create(160, 90, 1);
  ASSERT_TRUE(target.ok());
  ASSERT_TRUE(frame(*game, *target, 0.5).ok());
  const Scene* before = game->scene();
  // No MSAA: the fragment shaders write display values, no post pass.
  EXPECT_NE(game->renderer()->describe().find(" direct("), std::string::npos);
  const std::vector<CharacterInstance*> uploaded = game->renderer()->characters();
  SceneRenderOptions options = game->options();
  options.msaaOverride = 4;
  options.pcfKernelOverride = 1;
  ASSERT_TRUE(game->applyOptions(options).ok()) << game->lastError();
  EXPECT_EQ(game->scene(), before) << "the scene was reloaded";
  EXPECT_EQ(game->renderer()->characters(), uploaded) << "the models were uploaded again";
  const std::string described = game->renderer()->describe();
  EXPECT_NE(described.find("msaa 4,"), std::string::npos) << described;
  EXPECT_NE(described.find("shadow-sun(2048, hard)"), std::string::npos) << described;
  EXPECT_TRUE(game->lastError().empty());
  ASSERT_TRUE(frame(*game, *target, 0.6).ok());
  // The default (auto) sends only the dual-quaternion robot through the skin
  // cache; compute skinning sends every robot, a pass of its own.
  EXPECT_NE(described.find("skinning(skin cache: 1 primitives"), std::string::npos) << described;
  options.skinningOverride = Skinning::Compute;
  ASSERT_TRUE(game->applyOptions(options).ok()) << game->lastError();
  EXPECT_NE(game->renderer()->characters(), uploaded) << "the characters' skinning is uploaded with them";
  ASSERT_TRUE(frame(*game, *target, 0.7).ok());
  EXPECT_NE(game->renderer()->describe().find("skinning(skin cache: 4 primitives"), std::string::npos)
      << game->renderer()->describe();
  EXPECT_NE(game->settingName().find("skinning-compute"), std::string::npos) << game->settingName();
  EXPECT_GT(game->renderer()->stats().verticesDeformed, 0);
  // The scene file's own knobs, through the panel's parser: classic shading builds
  // the CLASSIC programs, and the name says what changed.
  for (const char* knob : {"shading=classic", "exposure=2", "tonemap=reinhard"})
    ASSERT_TRUE(demo::SceneGame::parseKnob(knob, options).ok()) << knob;
  EXPECT_FALSE(demo::SceneGame::parseKnob("exposure=3", options).ok());
  ASSERT_TRUE(game->applyOptions(options).ok()) << game->lastError();
  ASSERT_TRUE(frame(*game, *target, 0.8).ok());
  EXPECT_NE(game->renderer()->describe().find("shading: classic"), std::string::npos) << game->renderer()->describe();
  EXPECT_NE(game->settingName().find("classic"), std::string::npos) << game->settingName();
  EXPECT_NE(game->settingName().find("exposure2 tonemap-reinhard"), std::string::npos) << game->settingName();
}

// An impossible knob (more samples than the GL has) and a scene file that does not
// parse both leave the game as it was, the error kept for the panel.
TEST_P(TradePanel, FailuresKeepTheCurrentSceneAndShowTheirError) {
  auto game = startGame("cornell.json");
  ASSERT_TRUE(game);
  SceneRenderOptions options = game->options();
  options.msaaOverride = 64;
  EXPECT_FALSE(game->applyOptions(options).ok());
  EXPECT_NE(game->lastError().find("/render/msaa"), std::string::npos) << game->lastError();
  EXPECT_NE(game->renderer()->describe().find("msaa 1,"), std::string::npos);

  const std::string broken = (std::filesystem::temp_directory_path() / "engine_panel_broken.json").string();
  std::ofstream(broken) << "{\"lights\": [{\"type\": \"sun\", \"direction\": [0, -1, 0]}], \"primitives\": [";
  const Scene* before = game->scene();
  EXPECT_FALSE(game->switchScene(broken).ok());
  EXPECT_NE(game->lastError().find("engine_panel_broken.json"), std::string::npos) << game->lastError();
  EXPECT_EQ(game->scene(), before);
  EXPECT_EQ(game->renderer()->scene().path, kScenes + "cornell.json");
  auto target = RenderTarget::create(64, 36, 1);
  ASSERT_TRUE(target.ok());
  EXPECT_TRUE(frame(*game, *target, 0.0).ok());
  std::filesystem::remove(broken);

  ASSERT_TRUE(game->switchScene(kScenes + "materials.json").ok()) << game->lastError();
  EXPECT_TRUE(game->lastError().empty());
  EXPECT_EQ(game->renderer()->scene().path, kScenes + "materials.json");
}

// Paused, the poses hold however the runner's time moves; at speed 0.5 they
// advance by half of each step.
TEST_P(TradePanel, TimeControlsTakeOverFromTheRunner) {
  auto game = startGame("demo.json");
  ASSERT_TRUE(game);
  game->update(1.0, 0.1);
  EXPECT_EQ(game->scene()->time(), 1.0);
  demo::TimeControl& t = game->timeControl();
  t.taken = true;
  t.paused = true;
  game->update(5.0, 0.1);
  EXPECT_EQ(game->scene()->time(), 1.0);
  t.paused = false;
  t.speed = 0.5;
  game->update(5.1, 0.1);
  EXPECT_DOUBLE_EQ(game->scene()->time(), 1.05);
}

// Every pass of demo.json (the skin cache of its dual-quaternion robot, both sun
// maps in one, the world, post) has a GPU time
// once its query is back; none is negative, and the world costs something.
TEST_P(TradePanel, PassesReportGpuTimes) {
  auto game = startGame("demo.json");
  ASSERT_TRUE(game);
  auto target = RenderTarget::create(160, 90, 1);
  ASSERT_TRUE(target.ok());
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(frame(*game, *target, 0.1 * i).ok());
  glFinish();
  const auto times = game->renderer()->passTimes();
  std::vector<std::string> names;
  for (const auto& p : times) {
    names.push_back(p.pass);
    EXPECT_GE(p.gpuMs, 0.0) << p.pass;
  }
  // No post pass: demo.json needs no HDR target (its tone map is in the shaders).
  EXPECT_EQ(names, (std::vector<std::string>{"skinning", "shadow-sun", "world"}));
  for (const auto& p : times) {
    if (p.pass == "world") {
      EXPECT_GT(p.gpuMs, 0.0);
    }
  }
}

// The reference view traces what demo --mode raytrace|pathtrace writes: at the
// scene's own camera and time, the same size, spp and seed, the finished image is
// the same byte for byte (materials.json: glTF models through the scene layer).
TEST_P(TradePanel, TheReferenceIsWhatTheTracerWrites) {
  auto desc = loadSceneFile(kScenes + "materials.json");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  for (const bool path : {false, true}) {
    SCOPED_TRACE(path ? "pathtrace" : "raytrace");
    auto scene = Scene::load(*desc);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    demo::ReferenceRequest request;
    request.camera = desc->camera;
    request.width = 96;
    request.height = 54;
    request.settings.method = path ? rt::Method::Path : rt::Method::Whitted;
    request.settings.samplesPerPixel = path ? 2 : 1;
    request.settings.seed = 5;
    demo::ReferenceView view;
    ASSERT_TRUE(view.update(*scene, request).ok());
    ASSERT_TRUE(finish(view));
    const Image got = view.trace()->snapshot();
    rt::RenderSettings settings = request.settings;
    settings.width = request.width;
    settings.height = request.height;
    auto want = rt::raytraceScene(*desc, 0.0, settings);
    ASSERT_TRUE(want.ok()) << want.error().message;
    ASSERT_EQ(got.pixels.size(), want->image.pixels.size());
    auto diff = compareImages(got, want->image, 0);
    ASSERT_TRUE(diff.ok());
    EXPECT_EQ(diff->maxAbs, 0) << "mean " << diff->meanAbs << ", share over 0: " << diff->shareOver;
    // A second request for the same view keeps the finished trace.
    ProgressiveTrace* same = view.trace();
    ASSERT_TRUE(view.update(*scene, request).ok());
    EXPECT_EQ(view.trace(), same);
    view.release();
  }
}


// The reference's noise estimate (two halves of its samples) predicts its actual
// error against the converged image: the Cornell room path traced at 16 spp
// against 512 spp of another seed (whose own noise is 15 dB lower).
TEST_P(TradePanel, TheReferencesNoiseEstimateIsItsError) {
  auto desc = loadSceneFile(kScenes + "cornell.json");
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  auto scene = Scene::load(*desc);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  demo::ReferenceRequest request;
  request.camera = desc->camera;
  request.width = 64;
  request.height = 36;
  request.settings.method = rt::Method::Path;
  request.settings.samplesPerPixel = 16;
  request.settings.maxDepth = 16;
  request.settings.seed = 5;
  demo::ReferenceView view;
  ASSERT_TRUE(view.update(*scene, request).ok());
  // The trace runs on its own threads: two passes may be done already (under load
  // they were, once in ctest -j2). An estimate only from two passes on; read in
  // this order, as passes only grow.
  const bool estimated = view.trace()->noisePsnr().has_value();
  if (estimated) {
    EXPECT_GE(view.trace()->passesDone(), 2) << "an estimate before two passes";
  }
  ASSERT_TRUE(finish(view));
  const auto estimate = view.trace()->noisePsnr();
  ASSERT_TRUE(estimate);
  rt::RenderSettings truth = request.settings;
  truth.width = request.width;
  truth.height = request.height;
  truth.samplesPerPixel = 512;
  truth.seed = 9;
  auto converged = rt::raytraceScene(*desc, 0.0, truth);
  ASSERT_TRUE(converged.ok()) << converged.error().message;
  auto actual = compareImages(view.trace()->snapshot(), converged->image, 0);
  ASSERT_TRUE(actual.ok());
  std::printf("16 spp: noise estimate %.2f dB, actual PSNR against 512 spp %.2f dB\n", *estimate, actual->psnr);
  EXPECT_NEAR(*estimate, actual->psnr, kNoiseEstimateDb);
  view.release();
}

// Bookmarks: a saved view comes back in the next run (--bookmark N); a bookmark
// that is not there and a malformed file are errors naming the file.
TEST_P(TradePanel, BookmarksKeepViewsAcrossRuns) {
  const auto home = std::filesystem::current_path();
  // One folder per backend: ctest runs the two at once.
  const auto work = std::filesystem::temp_directory_path() / ("engine_bookmarks_" + std::string(backendName(GetParam())));
  std::filesystem::remove_all(work);
  std::filesystem::create_directories(work);
  std::filesystem::current_path(work);
  {
    auto game = startGame("cornell.json");
    ASSERT_TRUE(game);
    EXPECT_TRUE(game->bookmarks().all().empty());
    game->camera().position = {0.3, 1.1, -2.5};
    game->camera().yaw = 0.4;
    game->camera().pitch = -0.1;
    ASSERT_TRUE(game->bookmarkView().ok());
    EXPECT_TRUE(std::filesystem::exists(work / "out/bookmarks/cornell.json"));
  }
  auto desc = loadSceneFile(kScenes + "cornell.json");
  ASSERT_TRUE(desc.ok());
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  demo::SceneGame again(*desc, options, false);
  again.startAtBookmark(0);
  ASSERT_TRUE(again.init().ok());
  EXPECT_EQ(again.camera().position, glm::dvec3(0.3, 1.1, -2.5));
  EXPECT_EQ(again.camera().yaw, 0.4);
  EXPECT_EQ(again.camera().pitch, -0.1);
  demo::SceneGame missing(*desc, options, false);
  missing.startAtBookmark(3);
  const Status none = missing.init();
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("out/bookmarks/cornell.json: --bookmark 3: the file has 1 bookmarks"),
            std::string::npos)
      << none.error().message;
  { std::ofstream(work / "out/bookmarks/cornell.json") << R"([{"x": 1, "z": 2, "yaw": 0, "pitch": 0, "fovy": 60}])"; }
  demo::SceneGame malformed(*desc, options, false);
  malformed.startAtBookmark(0);
  const Status bad = malformed.init();
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("cornell.json: /0/y: expected a finite number"), std::string::npos)
      << bad.error().message;
  again.shutdown();
  missing.shutdown();
  malformed.shutdown();
  std::filesystem::current_path(home);
  std::filesystem::remove_all(work);
}

// "Add to table" needs a reference; with one, each press appends a row in
// bench/tradeoff's columns, the header written once; an unwritable path is an
// error naming it.
TEST_P(TradePanel, AddToTableAppendsRowsAgainstTheReference) {
  auto game = startGame("cornell.json");
  ASSERT_TRUE(game);
  // One folder per backend: ctest runs the two at once.
  const std::string csv = (std::filesystem::temp_directory_path() /
                           ("engine_panel_table_" + std::string(backendName(GetParam()))) / "results.csv")
                              .string();
  std::filesystem::remove_all(std::filesystem::path(csv).parent_path());
  EXPECT_NE(game->addToTable(csv).error().message.find("no reference"), std::string::npos);
  game->reference().mode = demo::ReferenceMode::Split;
  game->reference().divisor = 4;
  auto target = RenderTarget::create(96, 54, 1);
  ASSERT_TRUE(target.ok());
  const auto start = std::chrono::steady_clock::now();
  while (!game->reference().error) {
    ASSERT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120)) << game->reference().status;
    ASSERT_TRUE(frame(*game, *target, 0.0).ok());
  }
  EXPECT_GE(game->reference().error->spp, 1);
  EXPECT_GT(game->reference().error->psnr, 5.0);
  ASSERT_TRUE(game->addToTable(csv).ok());
  ASSERT_TRUE(game->addToTable(csv).ok());
  std::ifstream in(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "scene,family,setting,time_ms,psnr_db,mean_abs,ssim,reference");
  EXPECT_EQ(lines[1].rfind("cornell,panel,msaa1 ss1 shadow2048 pcf1 probe256,", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find(",pathtrace "), std::string::npos) << lines[1];
  const auto refused = game->addToTable("/proc/engine_no_such_dir/results.csv");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("/proc/engine_no_such_dir/results.csv"), std::string::npos);
  game->shutdown();
  std::filesystem::remove_all(std::filesystem::path(csv).parent_path());
}

// The CPU side of a frame is timed: posing at update, collecting and submitting
// the draws at render.
TEST_P(TradePanel, TheFrameTimesItsCpuWork) {
  auto game = startGame("demo.json");
  ASSERT_TRUE(game);
  auto target = RenderTarget::create(96, 54, 1);
  ASSERT_TRUE(target.ok());
  ASSERT_TRUE(frame(*game, *target, 0.3).ok());
  const SceneStats& s = game->renderer()->stats();
  EXPECT_GT(s.animationMs, 0.0);
  EXPECT_GT(s.cullMs, 0.0);
  EXPECT_GT(s.submitMs, 0.0);
}

// The scene layer decodes a scene file's images once (scene/scene_images.h): a
// material's PNG texture and the sky's HDR image are read when the scene loads, and
// neither a knob's rebuild of the renderer nor the reference traced beside it reads
// them again (both once read every image themselves).
TEST_P(TradePanel, AScenesImagesAreDecodedOnceAcrossARebuildAndAReference) {
  test::ScratchFolder folder;
  Image tiles;
  tiles.width = tiles.height = 4;
  tiles.pixels.assign(4 * 4 * 4, 200);
  ASSERT_TRUE(writePng((folder / "tiles.png").string(), tiles).ok());
  test::writeHdr(folder / "sky.hdr", 8, 4, std::vector<glm::vec3>(32, glm::vec3(0.4f, 0.5f, 0.7f)));
  const std::string path = (folder / "images.json").string();
  std::ofstream(path) << R"({"camera": {"position": [0, 1, 4], "target": [0, 0.5, 0]},
    "materials": {"tiled": {"color": [1, 1, 1], "texture": "tiles.png"}},
    "lights": [{"type": "sun", "direction": [0.3, 1, 0.2]}],
    "sky": {"image": "sky.hdr"},
    "primitives": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "tiled"}]})";
  auto desc = loadSceneFile(path);
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.iblSizeOverride = 16;
  const std::uint64_t before = imageFilesRead();
  demo::SceneGame game(*desc, options, true);
  ASSERT_TRUE(game.init().ok());
  EXPECT_EQ(imageFilesRead() - before, 2u) << "the texture and the sky, once each";
  const std::uint64_t loaded = imageFilesRead();
  auto target = RenderTarget::create(96, 54, 1);
  ASSERT_TRUE(target.ok());
  ASSERT_TRUE(frame(game, *target, 0.0).ok());
  options.msaaOverride = 2;
  ASSERT_TRUE(game.applyOptions(options).ok()) << game.lastError();
  ASSERT_TRUE(frame(game, *target, 0.0).ok());
  // The reference starts once the camera has held still for ten frames (a scene
  // without models is frozen in time).
  game.reference().mode = demo::ReferenceMode::Split;
  game.reference().pathTraced = false;
  for (int i = 0; i < 12 && !game.reference().view.running(); ++i) ASSERT_TRUE(frame(game, *target, 0.0).ok());
  ASSERT_TRUE(game.reference().view.running()) << game.reference().status;
  EXPECT_TRUE(game.reference().view.trace()->snapshot().width > 0);
  EXPECT_EQ(imageFilesRead(), loaded) << "an image was read again";
  game.shutdown();
}
