#pragma once
// The course room as the GPU tracer's image tests draw it (tests/gputrace/gpu_trace_test.cpp,
// the Whitted integrator; gpu_path_test.cpp, the path tracer): cornell_soft.json's
// room and area light, the point light of cornell.json, a sun through the open front,
// a box on the floor (12 flat triangles, through the scene file) and, in a BVH group
// of its own, a smooth bumpy patch with vertex normals on the left wall.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "asset/scene_file.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"

namespace engine::test {

inline rt::RtScene cornellScene(const std::string& file = "cornell.json") {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + file);
  EXPECT_TRUE(desc) << desc.error().message;
  auto scene = rt::analyticRtScene(*desc);
  EXPECT_TRUE(scene) << scene.error().message;
  return std::move(scene).value();
}

// `edit` may change the scene file's description (materials) before it is built;
// `sun` is the sun light added (intensity 0: none).
inline rt::RtScene roomWithMeshes(const std::function<void(SceneDesc&)>& edit = {}, LightDesc sun = [] {
  LightDesc l;  // through the open front, onto the floor near the camera
  l.direction = glm::normalize(glm::dvec3(0.2, 0.5, -1.0));
  l.intensity = 0.5f;
  return l;
}()) {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/cornell_soft.json");
  EXPECT_TRUE(desc) << desc.error().message;
  PrimitiveDesc box;
  box.type = PrimitiveType::Box;
  box.min = {-0.4, 0.0, 0.6};
  box.max = {0.3, 0.5, 1.1};
  box.material = 5;
  desc->primitives.push_back(box);
  if (edit) edit(*desc);
  auto built = rt::analyticRtScene(*desc);
  EXPECT_TRUE(built) << built.error().message;
  rt::RtScene scene = std::move(built).value();
  const rt::RtScene pointLit = cornellScene("cornell.json");
  for (const LightDesc& light : pointLit.lights()) scene.addLight(light);
  if (sun.intensity > 0.0f) scene.addLight(sun);
  rt::RtMesh patch;
  constexpr int kSide = 12;
  for (int j = 0; j <= kSide; ++j) {
    for (int i = 0; i <= kSide; ++i) {
      const float u = float(i) / kSide, v = float(j) / kSide;
      const float bump = 0.15f * std::sin(6.0f * u) * std::sin(5.0f * v);
      patch.positions.emplace_back(-2.2f + bump, 0.6f + 1.6f * v, 1.8f + 2.2f * u);
      patch.normals.push_back(glm::normalize(glm::vec3(1.0f, -0.75f * std::sin(6.0f * u) * std::cos(5.0f * v),
                                                       -0.9f * std::cos(6.0f * u) * std::sin(5.0f * v))));
    }
  }
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      const auto a = std::uint32_t(j * (kSide + 1) + i), b = a + 1, c = a + kSide + 1, d = c + 1;
      patch.indices.insert(patch.indices.end(), {a, d, b, a, c, d});  // facing +x, as the normals
    }
  }
  patch.material = 0;
  patch.group = scene.addGroup();
  EXPECT_TRUE(scene.addMesh(std::move(patch)));
  scene.build();
  return scene;
}

// The room in metallic-roughness, open to the sky (no ceiling, walls of 10 x 10): a
// smooth and a rough metal, a dielectric of ior 1.8 (KHR_materials_ior's f0), an
// emitter; a sun of 5 degrees high over the open top (the path tracer samples it as
// a cone and finds it by escaping BSDF rays; the Whitted tracer takes it as a delta)
// of `sunIntensity`, the gradient sky, fog. (The classic room's sun lights nothing:
// its ceiling, as wide as the far plane, shades the whole room.) `layers` may give
// the materials glTF's layers.
inline rt::RtScene pbrRoom(float sunIntensity = 1.5f, const std::function<void(SceneDesc&)>& layers = {}) {
  LightDesc sun;
  sun.direction = glm::normalize(glm::dvec3(0.3, 1.0, -0.4));
  sun.intensity = sunIntensity;
  sun.angleDegrees = 5.0f;
  rt::RtScene scene = roomWithMeshes(
      [&layers](SceneDesc& desc) {
        desc.primitives.erase(desc.primitives.begin() + 1);  // the ceiling
        // Walls 5 high, not as wide as the far plane: a well that deep lets no sun in.
        for (PrimitiveDesc& p : desc.primitives) p.extent = p.type == PrimitiveType::Plane ? 5.0 : p.extent;
        desc.materials[3].metallic = 1.0f;  // sphere1
        desc.materials[3].roughness = 0.35f;
        desc.materials[3].emission = glm::vec3(0.15f, 0.1f, 0.05f);
        desc.materials[4].metallic = 1.0f;  // the mirror
        desc.materials[4].roughness = 0.15f;
        desc.materials[5].roughness = 0.3f;  // blue: the sphere and the box
        desc.materials[5].layers.ior = 1.8f;
        if (layers) layers(desc);
      },
      sun);
  RenderDesc render = scene.render();
  render.shading = Shading::Pbr;
  scene.setRender(render);
  scene.setFog(FogDesc{true, 0.08f, glm::vec3(0.5f, 0.6f, 0.7f)});
  scene.setSky(SkyDesc{});
  return scene;
}

// Two spots added to a room: one shining down on the floor before the spheres with a
// soft edge (cones of 15 and 35 degrees, 1/d^2, shadows), and one on the left sphere
// with a sharp one (both cones 20 degrees, no falloff, no shadows).
inline void addSpots(rt::RtScene& scene) {
  LightDesc soft;
  soft.type = LightType::Spot;
  soft.position = {0.8, 2.9, 1.2};
  soft.direction = glm::normalize(soft.position - glm::dvec3(0.3, 0.0, 2.2));
  soft.innerConeDegrees = 15.0f;
  soft.outerConeDegrees = 35.0f;
  soft.falloff = true;
  soft.intensity = 6.0f;
  soft.color = {1.0f, 0.85f, 0.6f};
  scene.addLight(soft);
  LightDesc sharp;
  sharp.type = LightType::Spot;
  sharp.position = {-1.9, 2.6, 1.5};
  sharp.direction = glm::normalize(sharp.position - glm::dvec3(-1.2, 0.7, 3.0));
  sharp.innerConeDegrees = sharp.outerConeDegrees = 20.0f;
  sharp.intensity = 0.7f;
  sharp.color = {0.5f, 0.7f, 1.0f};
  sharp.shadows = false;
  scene.addLight(sharp);
}

// pbrRoom's materials with glTF's layers: a clear coat (smooth over the rough metal,
// and half a coat over the red wall), a sheen under red's coat, a thin film on the
// white walls and the mirror, and the blue sphere and box a tinted, absorbing volume.
inline void layeredMaterials(SceneDesc& desc) {
  desc.materials[3].layers.clearcoat = 1.0f;  // sphere1, a rough metal
  desc.materials[3].layers.clearcoatRoughness = 0.08f;
  desc.materials[1].layers.clearcoat = 0.5f;  // red
  desc.materials[1].layers.clearcoatRoughness = 0.3f;
  desc.materials[1].layers.sheenColor = glm::vec3(0.9f, 0.4f, 0.6f);  // under red's coat
  desc.materials[1].layers.sheenRoughness = 0.5f;
  desc.materials[5].layers.transmission = 0.9f;  // blue: a tinted, absorbing volume
  desc.materials[5].layers.thickness = 0.5f;
  desc.materials[5].layers.attenuationColor = glm::vec3(0.8f, 0.5f, 0.3f);
  desc.materials[5].layers.attenuationDistance = 0.7f;
  for (const int m : {0, 4}) {  // white, the mirror
    desc.materials[std::size_t(m)].layers.iridescence = 1.0f;
    desc.materials[std::size_t(m)].layers.iridescenceIor = 1.4f;
    desc.materials[std::size_t(m)].layers.iridescenceThicknessMax = 450.0f;
  }
}

}  // namespace engine::test
