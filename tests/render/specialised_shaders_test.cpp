// What a scene or a material leaves out is compiled out of its shaders, since
// llvmpipe runs code behind a uniform condition whatever the condition says: the
// scene's light counts (common/direct_light.glsl: SUN_LIGHT, POINT_LIGHTS), the PCF
// kernel (common/shadows.glsl: PCF_RADIUS) and, in classic shading, the highlight of
// a material that has none (CLASSIC_MATTE, ShaderVariant::matte). The image must be
// the one the uniforms give: the same scenes through a copy of the shaders that
// drops these defines (and loops over u_counts.x, checks u_sunDirection.w, reads the
// kernel's radius from the frame block, evaluates every highlight) must be the same
// bytes, for no sun and a sun, none to four point lights, classic and PBR, shapes
// and glTF models with a highlight and without; and for a terrain seen from above,
// the sun's near map and its far one both in view (the far one's kernel is always
// 3 x 3), with a hard sun and kernels of 3 and 5.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

constexpr int kWidth = 160, kHeight = 96;

// Four point lights, the first casting shadows, two with the 1/d^2 fall-off; the
// first `points` of them go into the scene, with a sun (from `sunDirection`) or
// without.
std::string lightsJson(bool sun, int points, const std::string& sunDirection) {
  const char* all[] = {
      R"({"type": "point", "position": [1.5, 2, 1.5], "intensity": 0.5, "shadows": true})",
      R"({"type": "point", "position": [-2, 1.5, 1], "color": [1, 0.4, 0.2], "intensity": 2, "falloff": true})",
      R"({"type": "point", "position": [0, 3, -2], "color": [0.3, 0.5, 1], "intensity": 0.4})",
      R"({"type": "point", "position": [2.5, 0.6, -0.5], "intensity": 1, "falloff": true})"};
  std::string list =
      sun ? R"({"type": "sun", "direction": )" + sunDirection + R"(, "intensity": 0.7, "shadows": true})" : "";
  for (int i = 0; i < points; ++i) list += std::string(list.empty() ? "" : ", ") + all[i];
  return "[" + list + "]";
}

// Hills under a low sun, seen from above: the near map's first metres, the band where
// it fades into the far map, and the far map's alone out to the horizon, each with
// shadows of hills in it. No ground plane.
constexpr const char* kTerrain = R"(
  "camera": {"position": [0, 40, 120], "target": [0, 10, 50], "fovy": 60, "far": 3000},
  "terrain": {"seed": 5, "size": 256, "spacing": 2, "height_scale": 40, "origin": [-128, 0, -128]},
  "fog": {"density": 0.001, "color": [0.6, 0.7, 0.85]},)";
constexpr const char* kShapes = R"(
  "camera": {"position": [0, 2.2, 5], "target": [0, 0.6, 0], "fovy": 50},)";
constexpr const char* kGround = R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "ground"},
                 )";

std::string sceneJson(bool sun, int points, const char* shading, bool terrain, int pcf) {
  return std::string("{") + (terrain ? kTerrain : kShapes) + R"(
  "lights": )" + lightsJson(sun, points, terrain ? "[-1, 0.45, 0.4]" : "[-0.4, 1, 0.3]") + R"(,
  "materials": {"ground": {"color": [0.6, 0.6, 0.55], "specular": 0.3, "shininess": 20},
                "red": {"color": [0.9, 0.1, 0.1], "roughness": 0.35}},
  "models": [{"path": "../models/character.gltf", "position": [-2.2, 0, 0.8], "clip": "Walk"},
             {"path": "../models/materials.gltf", "position": [0, 0, -1.5], "scale": 0.5}],
  "primitives": [)" + (terrain ? "" : kGround) +
         R"({"type": "sphere", "center": [0.8, 0.5, 0], "radius": 0.5, "material": "red"},
                 {"type": "box", "min": [-1.6, 0, -0.6], "max": [-0.6, 0.8, 0.4], "material": "ground"}],
  "sky": {"enabled": false, "background": [0.05, 0.05, 0.1]},
  "ambient": 0.1,
  "render": {"shading": ")" + shading + R"(", "shadow_filter": ")" + (pcf > 1 ? "pcf" : "hard") +
         R"(", "pcf_kernel": )" + std::to_string(pcf) + R"(}
})";
}

// A copy of the shaders that forgets the compiled-in constants, removed with it
// (also when an assertion ends the test early).
class ShadersWithoutThem {
 public:
  ShadersWithoutThem()
      : dir_(std::filesystem::temp_directory_path() / ("engine_specialised_shaders_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::copy(test::shaderDir(), dir_, std::filesystem::copy_options::recursive);
    const std::filesystem::path file = dir_ / "common" / "frame.glsl";
    std::stringstream text;
    text << std::ifstream(file).rdbuf();
    std::ofstream(file) << "#undef SUN_LIGHT\n#undef POINT_LIGHTS\n#undef CLASSIC_MATTE\n#undef PCF_RADIUS\n"
                        << text.str();
  }
  ~ShadersWithoutThem() { std::filesystem::remove_all(dir_); }
  ShadersWithoutThem(const ShadersWithoutThem&) = delete;
  ShadersWithoutThem& operator=(const ShadersWithoutThem&) = delete;
  std::string dir() const { return dir_.string(); }

 private:
  std::filesystem::path dir_;
};

struct Frame {
  Image image;
  std::string described;
};

Frame render(const SceneDesc& scene, const std::string& shaderDir) {
  SceneRenderOptions options;
  options.shaderDir = shaderDir;
  auto renderer = SceneRenderer::create(scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  auto target = RenderTarget::create(kWidth, kHeight, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  const Status status = (*renderer)->render((*renderer)->initialCamera(), kWidth, kHeight);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return {target->readPixels(), (*renderer)->describe()};
}

}  // namespace

class SpecialisedShaders : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(SpecialisedShaders);

TEST_P(SpecialisedShaders, DrawWhatTheirUniformsDraw) {
  const ShadersWithoutThem uncompiled;
  struct Case {
    bool sun;
    int points;
    const char* shading;
    bool terrain = false;
    int pcf = 3;
  };
  for (const Case c : {Case{true, 0, "classic"}, Case{true, 0, "pbr"}, Case{false, 1, "classic"},
                       Case{false, 2, "pbr"}, Case{true, 4, "classic"}, Case{true, 4, "pbr"},
                       Case{true, 0, "pbr", true, 3}, Case{true, 1, "classic", true, 1},
                       Case{true, 0, "pbr", true, 5}}) {
    const std::string what = std::string(c.sun ? "sun + " : "") + std::to_string(c.points) + " point";
    SCOPED_TRACE(what + ", " + c.shading + (c.terrain ? ", terrain, pcf " + std::to_string(c.pcf) : ""));
    auto scene = parseScene(sceneJson(c.sun, c.points, c.shading, c.terrain, c.pcf),
                            std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/specialised_shaders.json");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Frame compiled = render(*scene, test::shaderDir()), looped = render(*scene, uncompiled.dir());
    EXPECT_NE(compiled.described.find("lights compiled in: " + what), std::string::npos) << compiled.described;
    // Classic: the red sphere and the bricks and tiles (roughness 1) are matte, the
    // ground and the robot (roughness 0.6) are not. PBR has no matte variant.
    const bool classic = std::string(c.shading) == "classic";
    EXPECT_EQ(compiled.described.find("static+matte") != std::string::npos, classic) << compiled.described;
    EXPECT_EQ(compiled.described.find("lbs4+textured+matte") != std::string::npos, false) << compiled.described;
    ASSERT_EQ(compiled.image.pixels.size(), size_t(kWidth) * kHeight * 4);
    EXPECT_TRUE(compiled.image.pixels == looped.image.pixels);
  }
}
