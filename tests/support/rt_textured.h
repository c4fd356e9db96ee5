#pragma once
// The room of support/rt_room.h with textures sampled every way the tracers sample
// them, for the GPU tracers' image tests (tests/gputrace/gpu_trace_test.cpp,
// gpu_path_test.cpp): odd-sized images (their mipmaps halve unevenly), every wrap
// mode, a KHR_texture_transform on the second uv set, base colour, emissive and
// metallic-roughness textures on planes, spheres and meshes (one without uvs), uvs
// far outside [0, 1], alpha MASK and BLEND from a texture's alpha, a single-sided
// face seen from behind, the terrain's layered material on a bumpy grid, vertex
// colours; and an image sky (hashedSky).
#include <cmath>
#include <cstdint>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <unistd.h>

#include "asset/model_data.h"
#include "asset/texture_transform.h"
#include "radiance_file.h"
#include "raytrace/environment.h"
#include "raytrace/scene_builder.h"
#include "raytrace/terrain_material.h"
#include "rt_room.h"

namespace engine::test {

// A w x h image of hashed colours and alphas (each channel 0..255, alpha rising
// across it so that MASK and BLEND both have edges).
inline Image hashedImage(int w, int h, std::uint32_t seed) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint32_t v = (std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (seed * 83492791u);
      v ^= v >> 13;
      v *= 0x5bd1e995u;
      v ^= v >> 15;
      std::uint8_t* p = image.at(x, y);
      p[0] = std::uint8_t(v);
      p[1] = std::uint8_t(v >> 8);
      p[2] = std::uint8_t(v >> 16);
      p[3] = std::uint8_t(255 * x / std::max(1, w - 1));
    }
  }
  return image;
}

// A grid of (n + 1)^2 vertices over the quad corner + s a + t b (s, t in [0, 1]),
// with uvs uv0 + (s, t) * uvSpan and a second set (t, s); `bump` lifts it along the
// normal a x b by bump * sin sin.
inline rt::RtMesh uvGrid(const glm::vec3& corner, const glm::vec3& a, const glm::vec3& b, int n, glm::vec2 uv0,
                         glm::vec2 uvSpan, float bump = 0.0f) {
  rt::RtMesh mesh;
  const glm::vec3 up = glm::normalize(glm::cross(a, b));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float s = float(i) / float(n), t = float(j) / float(n);
      mesh.positions.push_back(corner + s * a + t * b + up * (bump * std::sin(7.0f * s) * std::sin(5.0f * t)));
      mesh.uvs.push_back(uv0 + glm::vec2(s, t) * uvSpan);
      mesh.uvs1.emplace_back(t, s);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const auto c = std::uint32_t(j * (n + 1) + i), d = c + 1, e = c + std::uint32_t(n) + 1, f = e + 1;
      mesh.indices.insert(mesh.indices.end(), {c, d, f, c, f, e});  // facing a x b
    }
  }
  return mesh;
}

// The mesh with a vertex colour (COLOR_0: linear RGBA, alpha 0.4-1) at each vertex.
inline rt::RtMesh withColors(rt::RtMesh mesh) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const float k = float(i % 7) / 6.0f;
    mesh.colors.emplace_back(0.4f + 0.6f * k, 1.0f - 0.5f * k, 0.7f, 0.4f + 0.6f * (1.0f - k));
  }
  return mesh;
}

// A lat-long Radiance image of hashed values (0.05-0.55, none that the tone map
// saturates), written to `path`, as the scene's environment: intensity 1.3, turned by
// 30 degrees.
// A file name of this process's own in the temporary folder.
inline std::filesystem::path temporaryFile(const std::string& name) {
  return std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
}

inline rt::Environment hashedSky(const std::filesystem::path& path) {
  constexpr int kWidth = 48, kHeight = 24;
  std::vector<glm::vec3> pixels;
  const Image hashed = hashedImage(kWidth, kHeight, 9);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) pixels.push_back(0.05f + glm::vec3(hashed.at(x, y)[0], hashed.at(x, y)[1], hashed.at(x, y)[2]) / 512.0f);
  }
  writeHdr(path, kWidth, kHeight, pixels);
  SkyDesc sky;
  sky.image = path.string();
  sky.intensity = 1.3f;
  sky.rotationDegrees = 30.0f;
  auto image = readLinearImage(sky.image);
  EXPECT_TRUE(image) << image.error().message;
  auto environment = rt::Environment::create(sky, std::nullopt, std::make_shared<const FloatImage>(std::move(image).value()));
  EXPECT_TRUE(environment) << environment.error().message;
  return std::move(environment).value();
}

// `edit` may change the materials (layers) before the scene is built.
inline rt::RtScene texturedRoom(const std::function<void(SceneDesc&)>& edit = {}) {
  // Materials 6 (MASK, single-sided), 7 (BLEND), 8 (the second uv set through a
  // transform) and 9 (the terrain's layers) after the room's six.
  rt::RtScene scene = roomWithMeshes([&edit](SceneDesc& desc) {
    desc.materials[0].textureScale = 0.8f;
    desc.materials[1].emission = glm::vec3(0.3f, 0.2f, 0.1f);
    desc.materials[3].textureScale = 2.0f;
    desc.materials[3].metallic = 0.7f;
    for (const char* name : {"mask", "blend", "transformed", "terrain"}) {
      MaterialDesc m;
      m.name = name;
      desc.materials.push_back(m);
    }
    if (edit) edit(desc);
  });
  using rt::RtTexture;
  using rt::TextureOrigin;
  const auto check = [](Status s) { EXPECT_TRUE(s) << s.error().message; };
  check(scene.setMaterialTexture(0, RtTexture(hashedImage(37, 23, 1), TextureOrigin::BottomLeft)
                                        .setWrap(TextureWrap::Repeat, TextureWrap::MirroredRepeat)));
  check(scene.setMaterialTexture(1, RtTexture(hashedImage(16, 9, 2), TextureOrigin::TopLeft)
                                        .setWrap(TextureWrap::ClampToEdge, TextureWrap::Repeat)));
  check(scene.setEmissiveTexture(1, RtTexture(hashedImage(5, 7, 3), TextureOrigin::TopLeft)));
  check(scene.setMaterialTexture(3, RtTexture(hashedImage(64, 31, 4), TextureOrigin::TopLeft)));
  check(scene.setMetallicRoughnessTexture(3, RtTexture(hashedImage(19, 19, 5), TextureOrigin::TopLeft,
                                                       rt::TextureEncoding::Linear)));
  check(scene.setMaterialTexture(6, RtTexture(hashedImage(12, 12, 6), TextureOrigin::TopLeft)));
  check(scene.setMaterialAlpha(6, AlphaMode::Mask, 1.0f, 0.5f));
  check(scene.setSingleSided(6, true));
  check(scene.setMaterialTexture(7, RtTexture(hashedImage(9, 14, 7), TextureOrigin::TopLeft)));
  check(scene.setMaterialAlpha(7, AlphaMode::Blend, 0.9f, 0.5f));
  const glm::mat3 turned = textureTransformMatrix(glm::vec2(0.3f, -0.2f), 0.7f, glm::vec2(2.5f, 1.5f));
  check(scene.setMaterialTexture(8, RtTexture(hashedImage(33, 17, 8), TextureOrigin::TopLeft)
                                        .setWrap(TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge)
                                        .setMapping(1, turned)));
  check(scene.setTerrainMaterial(9, rt::RtTerrainMaterial(0.0, 0.6f)));
  const int group = scene.addGroup();
  const auto add = [&](rt::RtMesh mesh, int material) {
    mesh.material = material;
    mesh.group = group;
    EXPECT_TRUE(scene.addMesh(std::move(mesh)));
  };
  // Cut-out leaves facing the camera (-z), a pane seen from the front and, turned
  // away from the camera, the same cut-out: single-sided, so it is not there.
  add(uvGrid({-1.9f, 1.6f, 2.2f}, {0.0f, 1.0f, 0.0f}, {1.2f, 0.0f, 0.0f}, 6, {-2.3f, 0.4f}, {5.5f, 3.0f}), 6);
  add(withColors(uvGrid({0.2f, 1.2f, 1.2f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.2f, 0.3f}, 3, {0.0f, 0.0f}, {1.0f, 1.0f})), 7);
  add(uvGrid({1.5f, 0.2f, 2.6f}, {0.8f, 0.0f, 0.0f}, {0.0f, 1.1f, 0.0f}, 3, {0.0f, 0.0f}, {1.0f, 1.0f}), 6);
  add(withColors(uvGrid({-0.6f, 2.0f, 4.9f}, {1.6f, 0.0f, 0.0f}, {0.0f, 0.9f, 0.0f}, 8, {-1.0f, -1.0f}, {3.0f, 3.0f}, 0.1f)), 8);
  add(uvGrid({-2.4f, 0.01f, 0.0f}, {0.0f, 0.0f, 2.4f}, {1.9f, 0.0f, 0.0f}, 24, {0.0f, 0.0f}, {40.0f, 40.0f}, 0.4f), 9);
  scene.build();
  return scene;
}

// A shipped scene (assets/scenes/`file`) as the tracers see it at time 0, its terrain
// selected for an image `height` pixels high.
inline rt::AnimatedRtScene shippedScene(const std::string& file, int height = 90) {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + file);
  EXPECT_TRUE(desc) << desc.error().message;
  auto traced = rt::AnimatedRtScene::create(*desc, 0.0, height);
  EXPECT_TRUE(traced) << traced.error().message;
  return std::move(traced).value();
}

// A small hashed image for layer slot `slot` of `material`, decoded as glTF decodes
// that slot (sRGB colours, linear factors), with a wrap and a seed of its own.
inline void addLayerTexture(rt::RtScene& scene, int material, TextureSlot slot, int w, int h) {
  const auto seed = std::uint32_t(20 + int(slot));
  const rt::TextureEncoding encoding = isSrgbSlot(slot) ? rt::TextureEncoding::Srgb : rt::TextureEncoding::Linear;
  rt::RtTexture texture(hashedImage(w, h, seed), rt::TextureOrigin::TopLeft, encoding);
  texture.setWrap(int(slot) % 2 ? TextureWrap::MirroredRepeat : TextureWrap::Repeat, TextureWrap::Repeat);
  const Status added = scene.setLayerTexture(material, slot, std::move(texture));
  EXPECT_TRUE(added) << added.error().message;
}

// A texture in each layer slot the tracers read, on the materials layeredMaterials
// gives layers: the volume's (5) specular weight and colour, transmission and
// thickness; the coated metal's (3) coat and its roughness; the red wall's (1) sheen
// colour and roughness; the white walls' (0) film and its thickness.
inline void addLayerTextures(rt::RtScene& scene) {
  using enum TextureSlot;
  for (const TextureSlot slot : {Specular, SpecularColor, Transmission, Thickness}) addLayerTexture(scene, 5, slot, 7, 5);
  for (const TextureSlot slot : {Clearcoat, ClearcoatRoughness}) addLayerTexture(scene, 3, slot, 6, 6);
  for (const TextureSlot slot : {SheenColor, SheenRoughness}) addLayerTexture(scene, 1, slot, 5, 9);
  for (const TextureSlot slot : {Iridescence, IridescenceThickness}) addLayerTexture(scene, 0, slot, 8, 3);
}

// support/rt_room.h's layered PBR room (`layers` on top of layeredMaterials) with a
// texture in each layer slot the tracers read: the volume's specular weight and
// colour, transmission and thickness; the coated metal's coat and its roughness; the
// sheen's colour and roughness on the red wall; the film's share and thickness on
// the white walls.
inline rt::RtScene layerTexturedRoom(const std::function<void(SceneDesc&)>& layers = {}) {
  rt::RtScene scene = pbrRoom(1.5f, [&layers](SceneDesc& desc) {
    layeredMaterials(desc);
    desc.materials[5].layers.specular = 0.8f;
    desc.materials[5].layers.specularColor = glm::vec3(1.0f, 0.7f, 0.9f);
    if (layers) layers(desc);
  });
  addLayerTextures(scene);
  return scene;
}

// Anisotropy needs a uv gradient to orient it: texturedRoom's grid on the back wall
// (its second uv set turned by a transform) made a brushed metal, in PBR under the
// gradient sky; `textured`: its direction and strength from a texture.
inline rt::RtScene brushedMetalRoom(bool textured = false) {
  rt::RtScene room = texturedRoom([](SceneDesc& desc) {
    MaterialDesc& m = desc.materials[8];
    m.metallic = 1.0f;
    m.roughness = 0.3f;
    m.layers.anisotropy = 0.8f;
    m.layers.anisotropyRotation = 0.5f;
  });
  if (textured) addLayerTexture(room, 8, TextureSlot::Anisotropy, 5, 4);
  RenderDesc render = room.render();
  render.shading = Shading::Pbr;
  room.setRender(render);
  room.setSky(SkyDesc{});
  return room;
}

}  // namespace engine::test
