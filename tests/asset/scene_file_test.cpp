// Scene files: the course room reads back exactly, and every error names the file,
// the JSON path and what was expected.
#include <gtest/gtest.h>

#include "../support/radiance_file.h"
#include "asset/scene_file.h"

using namespace engine;

namespace {
std::string errorOf(const std::string& text) {
  auto scene = parseScene(text, "s.json");
  return scene ? std::string("no error") : scene.error().message;
}
}  // namespace

TEST(SceneFile, CornellRoomIsTheCourseRoom) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->camera.position, glm::dvec3(0, 1.5, -3));
  EXPECT_EQ(scene->camera.forward, glm::dvec3(0, 0, 1));
  EXPECT_EQ(scene->camera.fovyDegrees, 60.0);
  EXPECT_TRUE(scene->camera.leftHanded);
  // Left-handed, looking along +z: +x is on the screen's right.
  EXPECT_EQ(scene->camera.right(), glm::dvec3(1, 0, 0));
  ASSERT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->lights[0].type, LightType::Point);
  EXPECT_EQ(scene->lights[0].position, glm::dvec3(0, 2.8, 2.0));
  EXPECT_FALSE(scene->lights[0].falloff);
  ASSERT_EQ(scene->primitives.size(), 8u);
  const PrimitiveDesc& mirror = scene->primitives[6];
  EXPECT_EQ(mirror.type, PrimitiveType::Sphere);
  EXPECT_EQ(mirror.center, glm::dvec3(0.9, 0.9, 3.4));
  EXPECT_EQ(mirror.radius, 0.9);
  const MaterialDesc& m = scene->materials[size_t(mirror.material)];
  EXPECT_FLOAT_EQ(m.reflection, 0.8f);
  EXPECT_FLOAT_EQ(m.diffuse, 0.2f);
  EXPECT_FLOAT_EQ(m.ambient, 0.0f);
  const MaterialDesc& red = scene->materials[size_t(scene->primitives[3].material)];
  EXPECT_EQ(red.color, glm::vec3(0.75f, 0.15f, 0.15f));
  EXPECT_EQ(scene->render.shading, Shading::Classic);
  EXPECT_EQ(scene->render.output, OutputCurve::Gamma22);
  EXPECT_EQ(scene->render.toneMap, ToneMap::None);
  EXPECT_FALSE(scene->sky.enabled);
}

TEST(SceneFile, ErrorsNameFilePathAndExpectation) {
  EXPECT_EQ(errorOf("{").rfind("s.json: not valid JSON: ", 0), 0u) << errorOf("{");
  EXPECT_EQ(errorOf("[]"), "s.json: /: expected an object");
  EXPECT_EQ(errorOf(R"({"camera": {"fovy": "wide"}})"), "s.json: /camera/fovy: expected a number");
  EXPECT_EQ(errorOf(R"({"camera": {"position": [1, 2]}})"),
            "s.json: /camera/position: expected an array of 3 numbers");
  EXPECT_EQ(errorOf(R"({"models": [{"path": "a.glb"}, {"path": "b.glb", "speed": "fast"}]})"),
            "s.json: /models/1/speed: expected a number");
  EXPECT_EQ(errorOf(R"({"lights": [{"type": "laser"}]})"),
            "s.json: /lights/0/type: \"laser\" is not one of: area, point, spot, sun");
  EXPECT_EQ(errorOf(R"({"primitives": [{"type": "sphere", "material": "gold"}]})"),
            "s.json: /primitives/0/material: no material \"gold\" in /materials");
  EXPECT_EQ(errorOf(R"({"render": {"pcf_kernel": 4}})"), "s.json: /render/pcf_kernel: expected an odd kernel width");
  EXPECT_EQ(errorOf(R"({"primitives": [{"type": "sphere", "radius": -1}]})"),
            "s.json: /primitives/0/radius: expected a number in [1e-09, 1e+12], got -1");
}

// A spot's file direction is the way it shines, kept as the way toward the light
// (LightDesc::direction), straight down by default; its cones in degrees, glTF's
// defaults where unset; and the cones' bad cases name the key.
TEST(SceneFile, ASpotShinesAlongItsDirectionWithinItsCones) {
  auto scene = parseScene(R"({"lights": [
      {"type": "spot", "position": [0, 4, 0], "direction": [0, 0, -2], "inner_cone": 10, "outer_cone": 25},
      {"type": "spot", "position": [1, 3, 0]}]})",
                          "s.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->lights.size(), 2u);
  const LightDesc& aimed = scene->lights[0];
  EXPECT_EQ(aimed.type, LightType::Spot);
  EXPECT_EQ(aimed.direction, glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(aimed.innerConeDegrees, 10.0f);
  EXPECT_EQ(aimed.outerConeDegrees, 25.0f);
  const LightDesc& plain = scene->lights[1];
  EXPECT_EQ(plain.direction, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_EQ(plain.innerConeDegrees, 0.0f);
  EXPECT_EQ(plain.outerConeDegrees, 45.0f);
  EXPECT_EQ(errorOf(R"({"lights": [{"type": "spot", "inner_cone": 30, "outer_cone": 20}]})"),
            "s.json: /lights/0/inner_cone: the inner cone must not be wider than the outer one");
  EXPECT_EQ(errorOf(R"({"lights": [{"type": "spot", "inner_cone": 50}]})"),
            "s.json: /lights/0/inner_cone: the inner cone must not be wider than the outer one");
  EXPECT_EQ(errorOf(R"({"lights": [{"type": "spot", "outer_cone": 91}]})"),
            "s.json: /lights/0/outer_cone: expected a number in [0, 90], got 91");
  EXPECT_EQ(errorOf(R"({"lights": [{"type": "sun", "inner_cone": 5}]})"),
            "s.json: /lights/0/inner_cone: only a spot light has a cone");
}

// fog.model volumetric: a medium with scattering and absorption per metre and an
// anisotropy, whose exponential stand-in's density is the mean extinction; the
// exponential fog keeps its keys; each bad case names its key.
TEST(SceneFile, AVolumetricFogIsAMediumWithAStandIn) {
  auto scene = parseScene(R"({"fog": {"model": "volumetric", "scattering": [0.1, 0.2, 0.3], "absorption": [0.3, 0, 0.3],
                                      "anisotropy": 0.7, "color": [0.5, 0.5, 0.5]}})",
                          "s.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(scene->fog.enabled);
  EXPECT_EQ(scene->fog.model, FogModel::Volumetric);
  EXPECT_EQ(scene->fog.scattering, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(scene->fog.absorption, glm::vec3(0.3f, 0.0f, 0.3f));
  EXPECT_FLOAT_EQ(scene->fog.anisotropy, 0.7f);
  EXPECT_FLOAT_EQ(scene->fog.density, 0.4f);
  auto plain = parseScene(R"({"fog": {"density": 0.05}})", "s.json");
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->fog.model, FogModel::Exponential);
  EXPECT_FLOAT_EQ(plain->fog.density, 0.05f);
  EXPECT_EQ(errorOf(R"({"fog": {"model": "volumetric", "scattering": [0.1, -0.2, 0.3]}})"),
            "s.json: /fog/scattering/1: expected a number in [0, 1e6] per metre");
  EXPECT_EQ(errorOf(R"({"fog": {"model": "volumetric", "absorption": [0.1, 1e300, 0.3]}})"),
            "s.json: /fog/absorption/1: expected a number within +-1e12");
  EXPECT_EQ(errorOf(R"({"fog": {"model": "volumetric", "anisotropy": 1}})"),
            "s.json: /fog/anisotropy: expected a number in [-0.999, 0.999], got 1");
  EXPECT_EQ(errorOf(R"({"fog": {"model": "volumetric", "density": 0.1}})"),
            "s.json: /fog/density: a volumetric fog takes scattering and absorption instead");
  EXPECT_EQ(errorOf(R"({"fog": {"scattering": [0.1, 0.1, 0.1]}})"),
            "s.json: /fog/scattering: only a volumetric fog (\"model\": \"volumetric\") has it");
  EXPECT_EQ(errorOf(R"({"fog": {"model": "cloudy"}})"),
            "s.json: /fog/model: \"cloudy\" is not one of: exponential, volumetric");
}

// The media: a height fog's falloff, the atmosphere's layers over Earth's defaults,
// boxes of fog; each bad case names its key.
TEST(SceneFile, MediaAreAHeightFogTheAirAndBoxes) {
  auto scene = parseScene(R"({"fog": {"model": "volumetric", "height_falloff": 0.01},
    "atmosphere": {"planet_radius": 3.4e6, "rayleigh": {"scale_height": 11000},
                   "mie": {"scattering": [1e-5, 2e-5, 3e-5], "anisotropy": 0.7}, "ozone": {"absorption": [0, 0, 0]},
                   "ground_albedo": [0.2, 0.1, 0.05]},
    "media": [{"type": "box", "min": [-1, 0, -1], "max": [1, 2, 1], "scattering": [0.5, 0.5, 0.5], "anisotropy": 0.3}]})",
                          "s.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_FLOAT_EQ(scene->fog.heightFalloff, 0.01f);
  const AtmosphereDesc& a = scene->atmosphere;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.planetRadius, 3.4e6);
  EXPECT_EQ(a.thickness, 100e3);
  EXPECT_FLOAT_EQ(a.rayleighScaleHeight, 11000.0f);
  EXPECT_EQ(a.rayleighScattering, AtmosphereDesc{}.rayleighScattering);
  EXPECT_EQ(a.mieScattering, glm::vec3(1e-5f, 2e-5f, 3e-5f));
  EXPECT_FLOAT_EQ(a.mieAnisotropy, 0.7f);
  EXPECT_EQ(a.ozoneAbsorption, glm::vec3(0.0f));
  EXPECT_EQ(a.groundAlbedo, glm::vec3(0.2f, 0.1f, 0.05f));
  ASSERT_EQ(scene->media.size(), 1u);
  EXPECT_EQ(scene->media[0].max, glm::dvec3(1, 2, 1));
  EXPECT_FLOAT_EQ(scene->media[0].anisotropy, 0.3f);
  EXPECT_FALSE(parseScene("{}", "s.json")->atmosphere.enabled);
  EXPECT_EQ(errorOf(R"({"fog": {"height_falloff": 0.1}})"),
            "s.json: /fog/height_falloff: only a volumetric fog (\"model\": \"volumetric\") has it");
  EXPECT_EQ(errorOf(R"({"atmosphere": {"planet_radius": 0}})"),
            "s.json: /atmosphere/planet_radius: expected a number in [1000, 1e+09], got 0");
  EXPECT_EQ(errorOf(R"({"atmosphere": {"mie": {"scale_height": 0}}})"),
            "s.json: /atmosphere/mie/scale_height: expected a number in [1, 1e+06], got 0");
  EXPECT_EQ(errorOf(R"({"atmosphere": {"ozone": {"width": 3}}})").rfind("s.json: /atmosphere/ozone/width: unknown key", 0), 0u);
  EXPECT_EQ(errorOf(R"({"atmosphere": {"ground_albedo": [0.5, 1.5, 0.5]}})"),
            "s.json: /atmosphere/ground_albedo/1: expected an albedo in [0, 1]");
  EXPECT_EQ(errorOf(R"({"media": [{"type": "sphere"}]})"), "s.json: /media/0/type: \"sphere\" is not one of: box");
  EXPECT_EQ(errorOf(R"({"media": [{"type": "box", "min": [0, 0, 0]}]})"), "s.json: /media/0: a box medium needs \"max\"");
  EXPECT_EQ(errorOf(R"({"media": [{"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "anisotropy": -1}]})"),
            "s.json: /media/0/anisotropy: expected a number in [-0.999, 0.999], got -1");
}

// render.ambient: unset falls back by the sky (IBL under one); a name not known
// is an error naming the choices.
TEST(SceneFile, AmbientChoice) {
  auto sky = parseScene("{}", "s.json");
  ASSERT_TRUE(sky.ok());
  EXPECT_FALSE(sky->render.ambient.has_value());
  EXPECT_EQ(ambientOf(*sky), Ambient::Ibl);
  auto bare = parseScene(R"({"sky": false})", "s.json");
  ASSERT_TRUE(bare.ok());
  EXPECT_EQ(ambientOf(*bare), Ambient::Hemisphere);
  auto sh = parseScene(R"({"render": {"ambient": "sh", "ibl_size": 64}})", "s.json");
  ASSERT_TRUE(sh.ok());
  EXPECT_EQ(ambientOf(*sh), Ambient::Sh);
  EXPECT_EQ(sh->render.iblSize, 64);
  EXPECT_EQ(errorOf(R"({"render": {"ambient": "bright"}})"),
            "s.json: /render/ambient: \"bright\" is not one of: hemisphere, ibl, sh");
  EXPECT_EQ(errorOf(R"({"render": {"ibl_size": 8}})").rfind("s.json: /render/ibl_size: ", 0), 0u);
}

TEST(SceneFile, UnknownKeysAreErrors) {
  const std::string e = errorOf(R"({"camera": {"fov": 60}})");
  EXPECT_EQ(e.rfind("s.json: /camera/fov: unknown key; expected one of:", 0), 0u) << e;
}

TEST(SceneFile, DegenerateGeometryIsRefused) {
  EXPECT_EQ(errorOf(R"({"camera": {"direction": [0, 0, 0]}})"),
            "s.json: /camera/direction: a direction must not be zero");
  EXPECT_EQ(errorOf(R"({"camera": {"direction": [0, 1, 0]}})"), "s.json: /camera: up is parallel to the view direction");
  EXPECT_EQ(errorOf(R"({"primitives": [{"type": "box", "min": [0, 0, 0], "max": [1, 0, 1]}]})"),
            "s.json: /primitives/0: a box needs min < max on every axis");
  EXPECT_EQ(errorOf(R"({"camera": {"near": 10, "far": 1}})"), "s.json: /camera: far must be greater than near");
}

TEST(SceneFile, ModelPathsAreRelativeToTheSceneFile) {
  auto scene = parseScene(R"({"models": [{"path": "../models/c.gltf", "clip": 2, "scale": 2}]})",
                          "assets/scenes/s.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->models[0].path, "assets/models/c.gltf");
  EXPECT_EQ(scene->models[0].clip, "2");
  EXPECT_EQ(scene->models[0].scale, glm::dvec3(2.0));
}

TEST(SceneFile, MissingFileNamesIt) {
  auto scene = loadSceneFile("/nonexistent/x.json");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().message, "/nonexistent/x.json: cannot open scene file");
}

// The sky's image is a path relative to the scene file, checked when the scene loads:
// each bad image is an error naming the scene file, the key and the image.
TEST(SceneFile, SkyImageIsResolvedAndChecked) {
  test::ScratchFolder folder;
  std::filesystem::create_directories(folder / "skies");
  test::writeHdr(folder / "skies/day.hdr", 2, 1, {glm::vec3(1.0f), glm::vec3(0.5f)});
  const std::string scenePath = (folder / "s.json").string();
  auto parse = [&](const std::string& sky) { return parseScene(R"({"sky": )" + sky + "}", scenePath); };
  auto errorIn = [&](const std::string& sky) {
    auto scene = parse(sky);
    return scene ? std::string("no error") : scene.error().message;
  };

  auto scene = parse(R"({"image": "skies/../skies/day.hdr", "intensity": 2.5, "rotation": -90})");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->sky.image, (folder / "skies/day.hdr").string());
  EXPECT_EQ(scene->sky.intensity, 2.5f);
  EXPECT_EQ(scene->sky.rotationDegrees, -90.0f);
  auto plain = parse("{}");
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->sky.image, "");
  EXPECT_EQ(plain->sky.intensity, 1.0f);
  EXPECT_EQ(plain->sky.rotationDegrees, 0.0f);

  const std::string at = scenePath + ": /sky/image: " + folder.path().string() + "/";
  EXPECT_EQ(errorIn(R"({"image": "night.hdr"})"), at + "night.hdr: no such file");
  test::writeBytes(folder / "empty.hdr", {});
  EXPECT_EQ(errorIn(R"({"image": "empty.hdr"})"), at + "empty.hdr: the file is empty (0 bytes)");
  test::writeBytes(folder / "text.png", {'h', 'e', 'l', 'l', 'o'});
  EXPECT_EQ(errorIn(R"({"image": "text.png"})"), at + "text.png: neither a Radiance .hdr nor a PNG image");
  const std::string zero = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n";
  test::writeBytes(folder / "zero.hdr", std::vector<std::uint8_t>(zero.begin(), zero.end()));
  EXPECT_EQ(errorIn(R"({"image": "zero.hdr"})"), at + "zero.hdr: image is 0x0 pixels; each side must be in [1, 16384]");
  EXPECT_EQ(errorIn(R"({"image": ""})"), scenePath + ": /sky/image: expected the path of a .hdr or PNG image");
  EXPECT_EQ(errorIn(R"({"image": 3})"), scenePath + ": /sky/image: expected a string");
  EXPECT_EQ(errorIn(R"({"intensity": -1})"), scenePath + ": /sky/intensity: expected a number in [0, 1e+09], got -1");
  EXPECT_EQ(errorIn(R"({"rotation": 400})"), scenePath + ": /sky/rotation: expected a number in [-360, 360], got 400");
  EXPECT_EQ(errorIn(R"({"rotation": "east"})"), scenePath + ": /sky/rotation: expected a number");
}
