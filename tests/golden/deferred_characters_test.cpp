// Characters shaded once a pixel (SceneRenderer's deferred characters: a surface
// pass, then a full-screen pass per material over the pixels it left) against the
// characters shaded where drawn (SceneRenderOptions::forwardCharacters), through
// both backends, in each way the renderer marks the pixels: one material where
// only the surface pass has drawn depth yet (the crowd, classic or PBR with sun
// shadows), several materials by the stencil beside a forward draw (the mixed
// crowd), and the stencil shared with the deferred terrain (demo.json, culled on
// the GPU and supersampled too).
//
// Why a level and not the same bytes: the surface keeps uv and the texture's level
// of detail as the forward draw had them, but the normal in two 16-bit snorms
// (within 5e-5 of its direction) and the position as a distance along the pixel's
// ray, which round differently in a float's last bits. Measured at 640x360: at most
// one level, in 2-26 of the 921,600 channels. A surface not written, read at the
// wrong pixel or shaded with the wrong material changes whole characters, by far
// more than a level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>

#include "app/runner.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "golden_views.h"
#include "scene_game.h"

using namespace engine;

namespace {

const std::string kAnchorScenes = std::string(ENGINE_SOURCE_DIR) + "/../shared/anchors/perf/scenes/";
const std::string kSampleModels = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/";

enum class Crowd { Classic, PbrShadows, Mixed, Demo, DemoCulled, DemoSupersampled };

struct CharacterCase {
  const char* name;
  Crowd crowd;
  bool stencil;  // the groups are marked by the stencil
};

const CharacterCase kCharacterCases[] = {{"crowd_classic", Crowd::Classic, false},
                                         {"crowd_pbr_shadows", Crowd::PbrShadows, false},
                                         {"crowd_mixed", Crowd::Mixed, true},
                                         {"demo_t0_5", Crowd::Demo, true},
                                         {"demo_t0_5_culled", Crowd::DemoCulled, true},
                                         {"demo_t0_5_ss2", Crowd::DemoSupersampled, true}};

bool usesDemo(Crowd crowd) { return crowd >= Crowd::Demo; }

// The crowd of ten CesiumMan (raylib's layout); Mixed replaces two of them by a
// Duck (another material: a second group) and a DamagedHelmet (normal-mapped: drawn
// forward among them).
Result<SceneDesc> crowdScene(Crowd crowd) {
  auto scene = loadSceneFile(kAnchorScenes + "cesiumman_10.json");
  if (!scene) return scene.error();
  if (crowd == Crowd::PbrShadows || crowd == Crowd::Mixed) {
    scene->render.shading = Shading::Pbr;
    scene->lights[0].shadows = true;
  }
  if (crowd == Crowd::Mixed) {
    scene->models[3].path = kSampleModels + "Duck/glTF-Binary/Duck.glb";
    scene->models[3].scale = glm::dvec3(0.5);
    scene->models[3].clip = "-1";  // neither has a clip: the rest pose
    scene->models[6].path = kSampleModels + "DamagedHelmet/glTF-Binary/DamagedHelmet.glb";
    scene->models[6].scale = glm::dvec3(0.4);
    scene->models[6].clip = "-1";
    scene->models[6].position.y += 0.5;
  }
  return scene;
}

struct Frame {
  Image image;
  std::string described;
};

Frame renderCharacterCase(Backend backend, const CharacterCase& c, bool forward) {
  auto scene = usesDemo(c.crowd) ? loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/demo.json")
                                 : crowdScene(c.crowd);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return {};
  SceneRenderOptions options;
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  options.gpuCullingOverride = c.crowd == Crowd::DemoCulled;
  options.supersampleOverride = c.crowd == Crowd::DemoSupersampled ? 2 : 0;
  options.forwardCharacters = forward;
  demo::SceneGame game(std::move(scene).value(), options);
  Frame frame;
  frame.image = test::goldenFrame(backend, game, usesDemo(c.crowd) ? 0.5 : 1.0,
                                  [&] { frame.described = game.renderer()->describe(); });
  return frame;
}

using CharacterParam = std::tuple<Backend, int>;
class DeferredCharacters : public ::testing::TestWithParam<CharacterParam> {};

TEST_P(DeferredCharacters, WithinLevelsOfTheCharactersShadedWhereDrawn) {
  const Backend backend = std::get<0>(GetParam());
  const CharacterCase& c = kCharacterCases[std::get<1>(GetParam())];
  if (!usesDemo(c.crowd) && !std::filesystem::exists(kAnchorScenes + "cesiumman_10.json"))
    GTEST_SKIP() << kAnchorScenes << " not found (../shared absent)";
  const Frame forward = renderCharacterCase(backend, c, true);
  const Frame deferred = renderCharacterCase(backend, c, false);
  ASSERT_FALSE(forward.image.pixels.empty());
  ASSERT_EQ(deferred.image.pixels.size(), forward.image.pixels.size());
  // Each path is the one asked for.
  EXPECT_EQ(forward.described.find("characters(deferred"), std::string::npos) << forward.described;
  EXPECT_NE(deferred.described.find("characters(deferred"), std::string::npos) << deferred.described;
  EXPECT_EQ(deferred.described.find("+ stencil,") != std::string::npos, c.stencil) << deferred.described;
  const auto [largest, differing] = test::channelDifference(forward.image, deferred.image);
  std::printf("%s: %zu of %zu channels differ, by at most %d\n", c.name, differing, forward.image.pixels.size(),
              largest);
  EXPECT_LE(largest, 1) << c.name;
  EXPECT_LT(differing, forward.image.pixels.size() / 2000) << c.name;
  if (largest > 1) {
    test::writeFailurePair(std::string("deferred_characters_") + c.name + "_" + std::string(backendName(backend)),
                           "forward", forward.image, "deferred", deferred.image);
  }
}

ENGINE_INSTANTIATE_GOLDEN_CASES_EGL(DeferredCharacters, kCharacterCases);

}  // namespace
