// The scene layer's one material table (scene/materials.h): a glTF material and a
// scene file's material come out of it as both renderers use them. The rasterizer's
// uniforms are recorded through render/material_uniforms.h, the very function its
// draws hand to gl::Program::set; the tracers' are their RtScene's HitMaterial and
// extras, built from the same table (raytrace/scene_builder.cpp). No GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "asset/scene_file.h"
#include "raytrace/scene_builder.h"
#include "render/material_uniforms.h"
#include "scene/materials.h"
#include "scene/scene.h"

namespace engine {
namespace {

const std::string kMaterialScenes = std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/";
const std::string kMaterialSamples = std::string(ENGINE_SOURCE_DIR) + "/../shared/gltf-samples/";

// The uniforms a draw is given, by name, as floats.
using Uniforms = std::map<std::string, std::vector<float>>;

struct UniformRecorder {
  Uniforms* out;
  void operator()(const char* name, float v) const { (*out)[name] = {v}; }
  void operator()(const char* name, const glm::vec2& v) const { (*out)[name] = {v.x, v.y}; }
  void operator()(const char* name, const glm::vec3& v) const { (*out)[name] = {v.x, v.y, v.z}; }
  void operator()(const char* name, const glm::vec4& v) const { (*out)[name] = {v.x, v.y, v.z, v.w}; }
};

Uniforms gltfUniforms(const SceneMaterial& m) {
  Uniforms u;
  forEachMaterialUniform(m, UniformRecorder{&u});
  return u;
}

Uniforms shapeUniforms(const SceneMaterial& m) {
  Uniforms u;
  forEachSurfaceUniform(m, UniformRecorder{&u});
  return u;
}

std::vector<float> floats(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The weights both shading models read: the rasterizer's uniforms against the
// tracer's HitMaterial, bit for bit.
void expectSurfaceAgrees(const Uniforms& u, const rt::HitMaterial& hit, const std::string& what) {
  SCOPED_TRACE(what);
  const std::vector<float>& base = u.at("u_baseColorFactor");
  EXPECT_EQ(std::vector<float>(base.begin(), base.begin() + 3), floats(hit.albedo));
  EXPECT_EQ(u.at("u_metallic")[0], hit.metallic);
  EXPECT_EQ(u.at("u_roughness")[0], hit.roughness);
  EXPECT_EQ(u.at("u_emissive"), floats(hit.emission));
  EXPECT_EQ(u.at("u_ambient")[0], hit.ambient);
  EXPECT_EQ(u.at("u_diffuse")[0], hit.diffuse);
  EXPECT_EQ(u.at("u_specular")[0], hit.specular);
  EXPECT_EQ(u.at("u_shininess")[0], hit.shininess);
  EXPECT_EQ(u.at("u_reflection")[0], hit.reflection);
}

// Every KHR layer the layered BRDF reads; the dielectric's f0 is the uniforms'
// parts multiplied (the tracer works it in double once per material).
void expectLayersAgree(const Uniforms& u, const rt::HitMaterial& hit, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(u.at("u_specularWeight")[0], hit.dielectricF90);
  const std::vector<float>& tint = u.at("u_specularColor");
  for (int c = 0; c < 3; ++c) {
    const float f0 = std::min(u.at("u_iorF0")[0] * tint[size_t(c)], 1.0f) * u.at("u_specularWeight")[0];
    EXPECT_NEAR(f0, hit.dielectricF0[c], 1e-6f) << "channel " << c;
  }
  EXPECT_EQ(u.at("u_clearcoat")[0], hit.clearcoat);
  EXPECT_EQ(u.at("u_clearcoatRoughness")[0], hit.clearcoatRoughness);
  EXPECT_EQ(u.at("u_transmission")[0], hit.transmission);
  EXPECT_EQ(u.at("u_thickness")[0], hit.thickness);
  EXPECT_EQ(u.at("u_ior")[0], hit.ior);
  EXPECT_EQ(u.at("u_attenuationDistance")[0], hit.attenuationDistance);
  EXPECT_EQ(u.at("u_attenuationColor"), floats(hit.attenuationColor));
  EXPECT_EQ(u.at("u_sheenColor"), floats(hit.sheenColor));
  EXPECT_EQ(u.at("u_sheenRoughness")[0], hit.sheenRoughness);
  EXPECT_EQ(u.at("u_anisotropy")[0], hit.anisotropy);
  EXPECT_EQ(u.at("u_anisotropyRotation")[0], hit.anisotropyRotation);
  EXPECT_EQ(u.at("u_iridescence")[0], hit.iridescence);
  EXPECT_EQ(u.at("u_iridescenceIor")[0], hit.iridescenceIor);
  EXPECT_EQ(u.at("u_iridescenceThickness")[1], hit.iridescenceThickness);
}

// glTF's alpha, sidedness, unlit and textures: the tracer holds a texture exactly
// where the rasterizer binds one (its normal maps and occlusion aside), of the
// image the table points at, decoded once with the model.
void expectExtrasAgree(const SceneMaterial& m, const Uniforms& u, const rt::RtScene& rt, int material,
                       const std::string& what) {
  SCOPED_TRACE(what);
  const rt::MaterialExtras& e = rt.extras(material);
  EXPECT_EQ(u.at("u_baseColorFactor")[3], e.alpha);
  EXPECT_EQ(u.at("u_alphaCutoff")[0], e.alphaCutoff);
  EXPECT_EQ(m.alphaMode, e.alphaMode);
  EXPECT_EQ(!m.doubleSided, e.singleSided);
  EXPECT_EQ(m.unlit, e.unlit);
  auto traced = [&](TextureSlot slot) {
    switch (slot) {
      case TextureSlot::BaseColor: return e.texture;
      case TextureSlot::Emissive: return e.emissiveTexture;
      case TextureSlot::MetallicRoughness: return e.metallicRoughnessTexture;
      default: return int(slot) >= kFirstLayerSlot ? e.layerTextures[size_t(slot) - kFirstLayerSlot] : -1;
    }
  };
  for (int i = 0; i < kTextureSlots; ++i) {
    const TextureSlot slot = TextureSlot(i);
    if (slot == TextureSlot::Normal || slot == TextureSlot::Occlusion || slot == TextureSlot::ClearcoatNormal) continue;
    const MaterialTexture& t = m.texture(slot);
    const int index = traced(slot);
    ASSERT_EQ(t.present(), index >= 0) << textureSlotName(slot);
    if (index < 0) continue;
    ASSERT_NE(t.decoded, nullptr) << textureSlotName(slot);
    EXPECT_EQ(rt.textures()[size_t(index)].width(), t.decoded->width) << textureSlotName(slot);
    EXPECT_EQ(rt.textures()[size_t(index)].texCoord(), t.sampling.texCoord) << textureSlotName(slot);
  }
}

std::shared_ptr<Scene> loadMaterialScene(const SceneDesc& desc) {
  auto scene = Scene::load(desc);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? *scene : nullptr;
}

SceneDesc materialsScene() {
  auto desc = loadSceneFile(kMaterialScenes + "materials.json");
  EXPECT_TRUE(desc.ok()) << desc.error().message;
  return desc.ok() ? *desc : SceneDesc{};
}

// Every glTF material of `desc`'s models and every scene material, through the table,
// into the rasterizer's uniforms and the tracer's materials: the same numbers.
// `layered` counts the glTF materials with layers.
void expectBothRenderersAgree(const SceneDesc& desc, int& layered) {
  auto scene = loadMaterialScene(desc);
  ASSERT_TRUE(scene);
  auto traced = rt::AnimatedRtScene::create(scene, 240);
  ASSERT_TRUE(traced.ok()) << traced.error().message;
  const rt::RtScene& rt = traced->scene();
  ASSERT_EQ(scene->materials().size(), desc.materials.size());
  for (size_t i = 0; i < scene->materials().size(); ++i) {
    const SceneMaterial& m = scene->materials()[i];
    expectSurfaceAgrees(shapeUniforms(m), rt.baseMaterial(int(i)), "scene material " + m.surface.name);
    EXPECT_EQ(m.texture(TextureSlot::BaseColor).present(), rt.extras(int(i)).texture >= 0) << m.surface.name;
  }
  for (size_t a = 0; a < scene->assets().size(); ++a) {
    const ModelAsset& asset = *scene->assets()[a];
    ASSERT_EQ(asset.materials.size(), asset.model.materials.size());
    // One more than the model has: glTF's default, for primitives without one.
    ASSERT_EQ(traced->assetMaterials(a).size(), asset.materials.size() + 1);
    for (size_t k = 0; k <= asset.materials.size(); ++k) {
      const SceneMaterial& m = gltfMaterialOf(asset.materials, int(k));
      const int material = traced->assetMaterials(a)[k];
      const Uniforms u = gltfUniforms(m);
      const std::string what = asset.model.path + ": material " + std::to_string(k) + " " + m.surface.name;
      expectSurfaceAgrees(u, rt.baseMaterial(material), what);
      expectExtrasAgree(m, u, rt, material, what);
      if (m.layered) {
        expectLayersAgree(u, rt.baseMaterial(material), what);
        ++layered;
      } else {
        EXPECT_EQ(u.count("u_clearcoat"), 0u) << what << ": a plain material's variant reads no layer";
      }
    }
  }
  EXPECT_EQ(scene->assets().size(), desc.models.size());
}

// The shipped material model (alpha MASK and BLEND, emissive, normal and
// metallic-roughness maps, double- and single-sided) beside a scene file's checker.
TEST(SceneMaterials, TheShippedMaterialSceneAgreesInBothRenderers) {
  int layered = 0;
  expectBothRenderersAgree(materialsScene(), layered);
}

// Khronos's samples of every KHR layer: the coat, sheen, film, transmission and
// volume, anisotropy, specular, unlit and transformed textures.
TEST(SceneMaterials, KhronosLayeredSamplesAgreeInBothRenderers) {
  const std::vector<std::string> samples = {
      "ClearCoatTest/glTF-Binary/ClearCoatTest.glb",       "SheenChair/glTF/SheenChair.gltf",
      "IridescenceLamp/glTF/IridescenceLamp.gltf",         "TransmissionTest/glTF-Binary/TransmissionTest.glb",
      "AttenuationTest/glTF-Binary/AttenuationTest.glb",   "AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb",
      "SpecularTest/glTF-Binary/SpecularTest.glb",         "UnlitTest/glTF-Binary/UnlitTest.glb",
      "TextureTransformTest/glTF/TextureTransformTest.gltf"};
  int found = 0, layered = 0;
  for (const std::string& sample : samples) {
    if (!std::filesystem::exists(kMaterialSamples + sample)) continue;
    ++found;
    SceneDesc desc = materialsScene();
    desc.models.resize(1);
    desc.models[0].path = kMaterialSamples + sample;
    SCOPED_TRACE(sample);
    expectBothRenderersAgree(desc, layered);
  }
  if (found == 0) GTEST_SKIP() << kMaterialSamples << " absent";
  EXPECT_GT(layered, found) << "the samples' layers were not compared";
}

// A primitive without a material: the rasterizer's default (white, dielectric,
// fully rough, hence no classic highlight), from the table like any other.
TEST(SceneMaterials, GltfsDefaultMaterialIsWhiteAndFullyRough) {
  const std::vector<SceneMaterial> none;
  const SceneMaterial& m = gltfMaterialOf(none, -1);
  const Uniforms u = gltfUniforms(m);
  EXPECT_EQ(u.at("u_baseColorFactor"), (std::vector<float>{1.0f, 1.0f, 1.0f, 1.0f}));
  EXPECT_EQ(u.at("u_metallic")[0], 0.0f);
  EXPECT_EQ(u.at("u_roughness")[0], 1.0f);
  EXPECT_EQ(u.at("u_specular")[0], 0.0f);
  EXPECT_FALSE(m.doubleSided);
  EXPECT_EQ(&gltfMaterialOf(none, 3), &m) << "out of range: the default too";
}

// Khronos's Triangle has no material: the tracer gives it glTF's default, as the
// rasterizer draws it (it took the scene's first material before).
TEST(SceneMaterials, APrimitiveWithoutAMaterialIsTracedWithTheDefault) {
  const std::string triangle = kMaterialSamples + "Triangle/glTF/Triangle.gltf";
  if (!std::filesystem::exists(triangle)) GTEST_SKIP() << triangle << " absent";
  SceneDesc desc = materialsScene();
  desc.models.resize(1);
  desc.models[0] = ModelDesc{};
  desc.models[0].path = triangle;
  auto scene = loadMaterialScene(desc);
  ASSERT_TRUE(scene);
  auto traced = rt::AnimatedRtScene::create(scene, 240);
  ASSERT_TRUE(traced.ok()) << traced.error().message;
  ASSERT_EQ(traced->instanceCount(), 1u);
  ASSERT_EQ(traced->instanceMeshes(0).size(), 1u);
  const int material = traced->instanceMeshes(0)[0].material;
  EXPECT_EQ(material, traced->assetMaterials(0).back());
  const SceneMaterial& fallback = gltfMaterialOf({}, -1);
  expectSurfaceAgrees(gltfUniforms(fallback), traced->scene().baseMaterial(material), "Triangle's default");
}

// The table's images are the model's and the scene's own, decoded once: no copy.
TEST(SceneMaterials, TexturesReferToTheImagesDecodedOnce) {
  auto scene = loadMaterialScene(materialsScene());
  ASSERT_TRUE(scene);
  const SceneMaterial& ground = scene->materials()[0];
  EXPECT_EQ(ground.texture(TextureSlot::BaseColor).decoded, scene->images().materialTexture(0));
  EXPECT_EQ(ground.origin, UvOrigin::BottomLeft);
  ASSERT_EQ(scene->assets().size(), 1u);
  const ModelAsset& asset = *scene->assets()[0];
  int textured = 0;
  for (size_t k = 0; k < asset.materials.size(); ++k) {
    for (int i = 0; i < kTextureSlots; ++i) {
      const MaterialTexture& t = asset.materials[k].textures[size_t(i)];
      EXPECT_EQ(t.image, asset.model.materials[k].image(TextureSlot(i)));
      if (!t.present()) continue;
      EXPECT_EQ(t.decoded, &asset.model.images[size_t(t.image)].image);
      ++textured;
    }
  }
  EXPECT_GT(textured, 0);
}

// A scene's tracer built with another scene's table is refused, naming the scene.
TEST(SceneMaterials, AnotherScenesTableIsRefused) {
  const SceneDesc desc = materialsScene();
  auto images = SceneImages::load(desc);
  ASSERT_TRUE(images.ok()) << images.error().message;
  const std::vector<SceneMaterial> table = sceneFileMaterials(desc, *images);
  SceneDesc other = desc;
  other.materials.push_back(MaterialDesc{});
  auto rt = rt::RtScene::fromSceneDesc(other, table, SceneEnvironment::of(other, images->sky));
  ASSERT_FALSE(rt.ok());
  EXPECT_NE(rt.error().message.find("materials.json"), std::string::npos) << rt.error().message;
}

}  // namespace
}  // namespace engine
