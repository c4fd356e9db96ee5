// glTF materials in the scene renderer, through the real programs (loader, scene
// file, SceneRenderer, both offscreen backends):
//  - a flat quad with a constant, tilted normal map lights like the same quad
//    without the map, turned by the same angle; and unlike the flat quad. Tilting
//    along the map's X checks the tangent, along Y the bitangent's sign (glTF's +Y
//    is up the image while its v runs down);
//  - an alpha MASK punches a hole (the background shows), a BLEND pane mixes with
//    what is behind it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "../support/gl_test.h"
#include "app/runner.h"
#include "asset/gltf_loader.h"
#include "asset/scene_file.h"
#include "core/image.h"
#include "core/linear_image.h"
#include "raytrace/scene_builder.h"
#include "raytrace/texture.h"
#include "scene_game.h"

using namespace engine;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr float kTilt = glm::radians(30.0f);

// A unit quad in the xy plane facing +z, uv (0,0) at the top-left, without
// TANGENT (the loader generates them). `material` is the glTF material object.
// Accessor 4 holds a second uv set, uv * 2 - 0.5 (past [0, 1] on every side), that
// no primitive reads unless `extra` (merged into the document's top level) says so.
void writeQuadModel(const fs::path& folder, const std::string& name, const json& material,
                    const std::vector<json>& images, const json& extra = json::object()) {
  const float positions[12] = {-0.5f, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f, -0.5f, 0, -0.5f, -0.5f, 0};
  const float normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::uint16_t indices[6] = {0, 3, 1, 1, 3, 2};
  const float uvs1[8] = {-0.5f, -0.5f, 1.5f, -0.5f, 1.5f, 1.5f, -0.5f, 1.5f};
  std::vector<char> bin(48 + 48 + 32 + 12 + 32);
  std::memcpy(bin.data(), positions, 48);
  std::memcpy(bin.data() + 48, normals, 48);
  std::memcpy(bin.data() + 96, uvs, 32);
  std::memcpy(bin.data() + 128, indices, 12);
  std::memcpy(bin.data() + 140, uvs1, 32);
  std::ofstream(folder / (name + ".bin"), std::ios::binary).write(bin.data(), std::streamsize(bin.size()));
  auto view = [](int offset, int length) { return json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}}; };
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}}}}}}},
      {"materials", {material}},
      {"buffers", {{{"byteLength", bin.size()}, {"uri", name + ".bin"}}}},
      {"bufferViews", {view(0, 48), view(48, 48), view(96, 32), view(128, 12), view(140, 32)}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {-0.5, -0.5, 0}}, {"max", {0.5, 0.5, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
        {{"bufferView", 4}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}},
  };
  if (!images.empty()) {
    doc["images"] = images;
    doc["textures"] = json::array();
    for (size_t i = 0; i < images.size(); ++i) doc["textures"].push_back({{"source", i}});
  }
  doc.update(extra);
  std::ofstream(folder / (name + ".gltf")) << doc.dump(1);
}

// A 4 x 4 image of one RGBA colour.
void writeFlatPng(const fs::path& path, glm::vec4 colour) {
  Image image(4, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = std::uint8_t(std::lround(std::clamp(colour[int(i % 4)], 0.0f, 1.0f) * 255.0f));
  ASSERT_TRUE(writePng(path.string(), image).ok());
}

// A scene with one model (rotated by `rotation` degrees) in front of the camera,
// lit by a sun from the upper right front (not symmetric: tilting toward x and
// toward y give different values), black background, no tone map, mid-grey
// values far from clipping.
fs::path writeScene(const fs::path& folder, const std::string& name, const std::string& model,
                    glm::vec3 rotation, const json& extraModels = json::array(), float sun = 0.6f) {
  json models = json::array({{{"path", model + ".gltf"}, {"rotation", {rotation.x, rotation.y, rotation.z}}}});
  for (const json& m : extraModels) models.push_back(m);
  const json scene = {
      {"camera", {{"position", {0, 0, 3}}, {"target", {0, 0, 0}}, {"fovy", 30}, {"near", 0.1}, {"far", 20}}},
      {"lights", {{{"type", "sun"}, {"direction", {0.45, 0.65, 0.6}}, {"color", {1, 1, 1}}, {"intensity", sun}}}},
      {"models", models},
      {"sky", {{"enabled", false}, {"background", {0, 0, 0}}}},
      {"render", {{"shading", "pbr"}, {"tonemap", "none"}, {"output", "srgb"}}},
  };
  const fs::path path = folder / (name + ".json");
  std::ofstream(path) << scene.dump(1);
  return path;
}

class MaterialTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    dir_ = fs::path(ENGINE_BINARY_DIR) / "test-output" / "material_test" /
           (std::string(backendName(GetParam())) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }

  Image render(const fs::path& scenePath) {
    auto scene = loadSceneFile(scenePath.string());
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    if (!scene) return {};
    SceneRenderOptions options;
    options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
    demo::SceneGame game(std::move(scene).value(), options);
    RunOptions run;
    run.width = 64;
    run.height = 64;
    run.frames = 1;
    run.debugGl = true;
    Image image;
    auto status = runHeadless(GetParam(), game, run, &image);
    EXPECT_TRUE(status.ok()) << status.error().message;
    return image;
  }

  fs::path dir_;
};

// Mean RGB (0..255) of the 6 x 6 pixels around (x, y).
glm::vec3 meanAround(const Image& image, int cx, int cy) {
  glm::vec3 sum(0.0f);
  for (int y = cy - 3; y < cy + 3; ++y)
    for (int x = cx - 3; x < cx + 3; ++x) {
      const std::uint8_t* p = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
      sum += glm::vec3(p[0], p[1], p[2]);
    }
  return sum / 36.0f;
}

float largest(glm::vec3 v) { return std::max({v.x, v.y, v.z}); }
float smallest(glm::vec3 v) { return std::min({v.x, v.y, v.z}); }
float largestDifference(glm::vec3 a, glm::vec3 b) { return largest(glm::abs(a - b)); }

TEST_P(MaterialTest, TiltedNormalMapLightsLikeTheTiltedQuad) {
  // Tilt along the map's X (toward the tangent, +x) and along its Y (toward the
  // bitangent, up the image: +y in the world).
  struct Case {
    const char* name;
    glm::vec3 mapNormal;      // tangent space
    glm::vec3 quadRotation;   // degrees, turning the plain quad's +z normal to the same place
  };
  const Case cases[] = {
      {"tilt_x", {std::sin(kTilt), 0.0f, std::cos(kTilt)}, {0.0f, glm::degrees(kTilt), 0.0f}},
      {"tilt_y", {0.0f, std::sin(kTilt), std::cos(kTilt)}, {-glm::degrees(kTilt), 0.0f, 0.0f}},
  };
  writeQuadModel(dir_, "plain", {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}}, {});
  const Image flat = render(writeScene(dir_, "flat", "plain", glm::vec3(0.0f)));
  ASSERT_EQ(flat.width, 64);
  const glm::vec3 flatColour = meanAround(flat, 32, 32);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    writeFlatPng(dir_ / (std::string(c.name) + ".png"), glm::vec4(c.mapNormal * 0.5f + 0.5f, 1.0f));
    writeQuadModel(dir_, std::string(c.name) + "_mapped",
                   {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                    {"normalTexture", {{"index", 0}}}},
                   {{{"uri", std::string(c.name) + ".png"}}});
    const Image mapped = render(writeScene(dir_, std::string(c.name) + "_mapped", std::string(c.name) + "_mapped", glm::vec3(0.0f)));
    const Image turned = render(writeScene(dir_, std::string(c.name) + "_turned", "plain", c.quadRotation));
    ASSERT_EQ(mapped.width, 64);
    ASSERT_EQ(turned.width, 64);
    // At the centre the two surfaces share position, normal and view direction.
    // The map stores the normal in 8 bits (up to 0.5/255 per component, about 0.2
    // degrees), which moves the lit value by about one output level: 3 levels.
    const glm::vec3 m = meanAround(mapped, 32, 32), t = meanAround(turned, 32, 32);
    std::printf("%s: flat %.1f %.1f %.1f, normal-mapped %.1f %.1f %.1f, turned %.1f %.1f %.1f\n", c.name, flatColour.x,
                flatColour.y, flatColour.z, m.x, m.y, m.z, t.x, t.y, t.z);
    EXPECT_LE(largestDifference(m, t), 3.0f) << "mapped " << m.x << "," << m.y << "," << m.z << " turned " << t.x << ","
                                             << t.y << "," << t.z;
    // A 30 degree tilt toward this sun brightens the quad by more than 10 levels
    // (N.L from 0.60 to 0.75 toward x, 0.85 toward y); a map that did nothing, or
    // tilted the wrong way (N.L 0.30 and 0.20), fails here.
    EXPECT_GE(smallest(m - flatColour), 10.0f) << "flat " << flatColour.x << " mapped " << m.x;
  }
}

TEST_P(MaterialTest, MaskCutsAndBlendMixes) {
  // Left half of the mask texture transparent, right half opaque: alpha < 0.5 is
  // discarded, so the left of the quad shows the black background.
  Image mask(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      std::uint8_t* p = &mask.pixels[(size_t(y) * 8 + size_t(x)) * 4];
      p[0] = p[1] = p[2] = 255;
      p[3] = x < 4 ? 0 : 255;
    }
  ASSERT_TRUE(writePng((dir_ / "mask.png").string(), mask).ok());
  writeQuadModel(dir_, "masked",
                 {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}},
                  {"alphaMode", "MASK"}},
                 {{{"uri", "mask.png"}}});
  const Image masked = render(writeScene(dir_, "masked", "masked", glm::vec3(0.0f)));
  ASSERT_EQ(masked.width, 64);
  EXPECT_LE(largest(meanAround(masked, 24, 32)), 1.0f) << "the masked-out half is drawn";
  EXPECT_GE(smallest(meanAround(masked, 40, 32)), 40.0f) << "the opaque half is missing";

  // A red pane at alpha 0.5 in front of the white quad: red survives, green and
  // blue halve (blending in linear light, so the encoded value drops less than half).
  writeQuadModel(dir_, "white", {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}, {});
  writeQuadModel(dir_, "pane",
                 {{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 0.5}}, {"metallicFactor", 0.0}}},
                  {"alphaMode", "BLEND"}},
                 {});
  const Image behind = render(writeScene(dir_, "white", "white", glm::vec3(0.0f)));
  const json pane = json::array({{{"path", "pane.gltf"}, {"position", {0.0, 0.0, 0.5}}}});
  const Image blended = render(writeScene(dir_, "blended", "white", glm::vec3(0.0f), pane));
  ASSERT_EQ(blended.width, 64);
  const glm::vec3 w = meanAround(behind, 32, 32), b = meanAround(blended, 32, 32);
  std::printf("white quad %.1f %.1f %.1f; behind the red pane %.1f %.1f %.1f\n", w.x, w.y, w.z, b.x, b.y, b.z);
  EXPECT_LT(b.g, w.g - 20.0f) << "the pane does not darken green: " << b.g << " vs " << w.g;
  EXPECT_GT(b.g, 20.0f) << "the pane is opaque: green " << b.g;
  EXPECT_GT(b.r, b.g + 20.0f) << "the pane is not red";
}

// The GPU and the CPU tracers read a texture the same way: an emissive quad (black
// base colour, no light, no tone map: each pixel is the emissive texel, sRGB out)
// samples TEXCOORD_1 (past [0, 1]) through a KHR_texture_transform with offset,
// rotation and scale, mirrored in s and clamped in t. Every pixel inside the quad
// must be RtTexture's sample at that pixel's uv, set up from the loaded material as
// the tracers' scene builder does.
TEST_P(MaterialTest, UvTransformAndWrapMatchTheTracersTexture) {
  Image texels(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      std::uint8_t* p = texels.at(x, y);
      p[0] = std::uint8_t(30 + 60 * x);
      p[1] = std::uint8_t(20 + 70 * y);
      p[2] = std::uint8_t((x * 3 + y * 5) % 4 * 80);
      p[3] = 255;
    }
  ASSERT_TRUE(writePng((dir_ / "texels.png").string(), texels).ok());
  const json transform = {{"offset", {0.3, -0.2}}, {"rotation", 0.5}, {"scale", {1.3, 0.8}}};
  const json extra = {
      {"extensionsUsed", {"KHR_texture_transform"}},
      {"samplers", {{{"wrapS", 33648}, {"wrapT", 33071}, {"magFilter", 9729}, {"minFilter", 9729}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 4}}},
            {"indices", 3},
            {"material", 0}}}}}}},
  };
  writeQuadModel(dir_, "transformed",
                 {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                  {"emissiveFactor", {1, 1, 1}},
                  {"emissiveTexture", {{"index", 0}, {"texCoord", 1}, {"extensions", {{"KHR_texture_transform", transform}}}}}},
                 {{{"uri", "texels.png"}}}, extra);
  auto model = loadGltf((dir_ / "transformed.gltf").string());
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_TRUE(model->warnings.empty()) << model->warnings[0];
  const TextureSlotData& slot = model->materials[0].texture(TextureSlot::Emissive);
  rt::RtTexture cpu(model->images[0].image, rt::TextureOrigin::TopLeft);
  cpu.setWrap(slot.sampler.wrapS, slot.sampler.wrapT).setMapping(slot.texCoord, slot.uvTransform);

  const Image gpu = render(writeScene(dir_, "transformed", "transformed", glm::vec3(0.0f), json::array(), 0.0f));
  ASSERT_EQ(gpu.width, 64);
  // The camera at z = 3 with fovy 30 sees +-3 tan 15 degrees; the quad spans +-0.5.
  const float half = 3.0f * std::tan(glm::radians(15.0f));
  int compared = 0, worst = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const glm::vec2 world(((x + 0.5f) / 64.0f * 2.0f - 1.0f) * half, (1.0f - (y + 0.5f) / 64.0f * 2.0f) * half);
      const glm::vec2 uv0(world.x + 0.5f, 0.5f - world.y);
      // Two pixels clear of the quad's edges, where coverage decides.
      if (glm::any(glm::lessThan(uv0, glm::vec2(0.05f))) || glm::any(glm::greaterThan(uv0, glm::vec2(0.95f)))) continue;
      const glm::vec3 linear = cpu.sample(rt::HitUv(uv0, uv0 * 2.0f - 0.5f));
      const std::uint8_t* p = &gpu.pixels[(size_t(y) * 64 + size_t(x)) * 4];
      for (int c = 0; c < 3; ++c) {
        const float v = linear[c] <= 0.0031308f ? linear[c] * 12.92f : 1.055f * std::pow(linear[c], 1.0f / 2.4f) - 0.055f;
        worst = std::max(worst, std::abs(int(p[c]) - int(std::lround(v * 255.0f))));
      }
      ++compared;
    }
  std::printf("uv transform and wrap: %d pixels, worst %d levels from the tracer's texture\n", compared, worst);
  EXPECT_GT(compared, 1000);
  // GL filters with fixed-point weights (llvmpipe: 8 bits) and encodes its own way:
  // measured 1 level at most, on both backends. A wrong rotation, offset, scale, uv
  // set or wrap moves whole texels (60 levels and more apart here): the shader
  // reading set 0 measured 231, one skipping the matrix 239.
  EXPECT_LE(worst, 3) << "over " << compared << " pixels";
}

// KHR_materials_unlit: the quad shows its base colour as it is, whatever the sun
// and the quad's angle to it (tone map none, sRGB out: 0.2, 0.5, 0.8 encode to
// 124, 188, 231), and the Whitted and path tracers show the same colour.
TEST_P(MaterialTest, UnlitShowsItsBaseColourUnderAnyLight) {
  const json unlit = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.5, 0.8, 1.0}}}},
                      {"extensions", {{"KHR_materials_unlit", json::object()}}}};
  writeQuadModel(dir_, "unlit", unlit, {}, {{"extensionsUsed", {"KHR_materials_unlit"}}});
  const glm::vec3 want(124.0f, 188.0f, 231.0f);
  for (const auto& [rotation, sun] : {std::pair{glm::vec3(0.0f), 0.6f}, std::pair{glm::vec3(0, 40, 0), 3.0f}}) {
    const fs::path scene = writeScene(dir_, "unlit_scene", "unlit", rotation, json::array(), sun);
    const glm::vec3 raster = meanAround(render(scene), 32, 32);
    EXPECT_LE(largestDifference(raster, want), 1.0f) << "raster " << raster.x << " " << raster.y << " " << raster.z;
    auto desc = loadSceneFile(scene.string());
    ASSERT_TRUE(desc.ok()) << desc.error().message;
    for (rt::Method method : {rt::Method::Whitted, rt::Method::Path}) {
      rt::RenderSettings settings;
      settings.width = settings.height = 64;
      settings.samplesPerPixel = 4;
      settings.method = method;
      auto traced = rt::raytraceScene(*desc, 0.0, settings);
      ASSERT_TRUE(traced.ok()) << traced.error().message;
      const glm::vec3 t = meanAround(traced->image, 32, 32);
      EXPECT_LE(largestDifference(t, want), 1.0f) << (method == rt::Method::Path ? "path " : "whitted ") << t.x << " "
                                                  << t.y << " " << t.z;
    }
  }
}

ENGINE_INSTANTIATE_OFFSCREEN(MaterialTest);

}  // namespace
