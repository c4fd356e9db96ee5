#pragma once
// The course room as the GPU tracer's image tests draw it (tests/gl/gpu_trace_test.cpp,
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

namespace engine::test {

inline rt::RtScene cornellScene(const std::string& file = "cornell.json") {
  auto desc = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + file);
  EXPECT_TRUE(desc) << desc.error().message;
  auto scene = rt::RtScene::fromSceneDesc(*desc);
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
  auto built = rt::RtScene::fromSceneDesc(*desc);
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

}  // namespace engine::test
