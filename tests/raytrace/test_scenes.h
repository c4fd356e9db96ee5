#pragma once
// Small scenes built in code for the ray tracer's tests (render_test.cpp,
// path_tracer_test.cpp): a course material, a point light, a camera, an empty room;
// and the project's scene files as the tracer builds them.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "asset/scene_file.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"

namespace rt = engine::rt;
using engine::CameraDesc;
using engine::LightDesc;
using engine::LightType;
using engine::MaterialDesc;

inline MaterialDesc classic(glm::vec3 color, float ambient, float diffuse, float reflection = 0.0f) {
  MaterialDesc m;
  m.color = color;
  m.ambient = ambient;
  m.diffuse = diffuse;
  m.reflection = reflection;
  return m;
}

inline LightDesc pointLight(glm::dvec3 position) {
  LightDesc l;
  l.type = LightType::Point;
  l.position = position;
  return l;
}

inline CameraDesc lookAt(glm::dvec3 eye, glm::dvec3 target, double fovy = 60.0) {
  CameraDesc c;
  c.position = eye;
  c.forward = glm::normalize(target - eye);
  c.up = glm::dvec3(0, 1, 0);
  if (std::abs(c.forward.y) > 0.99) c.up = glm::dvec3(0, 0, 1);
  c.fovyDegrees = fovy;
  c.leftHanded = true;
  return c;
}

// A classic-shaded scene with no sky (escaping rays are black), as the course.
inline rt::RtScene emptyScene(const CameraDesc& camera) {
  rt::RtScene scene;
  scene.setCamera(camera);
  engine::SkyDesc sky;
  sky.enabled = false;
  scene.setSky(sky);
  engine::RenderDesc render;
  render.shading = engine::Shading::Classic;
  render.toneMap = engine::ToneMap::None;
  render.output = engine::OutputCurve::Gamma22;
  scene.setRender(render);
  return scene;
}

// assets/scenes/`name` built for the ray tracer at time 0 and 240 rows.
inline rt::RtScene sceneFile(const std::string& name) {
  auto desc = engine::loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/" + name);
  EXPECT_TRUE(desc) << desc.error().message;
  auto scene = rt::buildRtScene(*desc, 0.0, 240);
  EXPECT_TRUE(scene) << scene.error().message;
  return std::move(*scene);
}

// The path tracer's settings for a w x h image of spp samples a pixel.
inline rt::RenderSettings pathSettings(int w, int h, int spp, int maxDepth = 64) {
  rt::RenderSettings s;
  s.method = rt::Method::Path;
  s.width = w;
  s.height = h;
  s.samplesPerPixel = spp;
  s.maxDepth = maxDepth;
  return s;
}

// An image's mean colour, in double.
inline glm::dvec3 meanOf(const rt::Framebuffer& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& p : image.pixels) sum += glm::dvec3(p);
  return sum / double(image.pixels.size());
}

// A volumetric fog of the given coefficients per metre, Henyey-Greenstein's g and
// height falloff (0: homogeneous).
inline engine::FogDesc volumetricFog(glm::vec3 scattering, glm::vec3 absorption, float g = 0.0f, float falloff = 0.0f) {
  engine::FogDesc fog;
  fog.enabled = true;
  fog.model = engine::FogModel::Volumetric;
  fog.scattering = scattering;
  fog.absorption = absorption;
  fog.anisotropy = g;
  fog.heightFalloff = falloff;
  return fog;
}

// What a camera at the origin looking along +z (vertical field fovy) sees, on
// average over a side x side image, of a wall emitting 1 at z = `distance` through a
// medium that only absorbs: exp(-absorption * the distance along each pixel
// centre's ray), per channel.
inline glm::dvec3 beerLambertMean(int side, double fovyDegrees, double distance, glm::vec3 absorption) {
  const double tanHalf = std::tan(glm::radians(fovyDegrees) / 2.0);
  glm::dvec3 sum(0.0);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const double px = (2.0 * (x + 0.5) / side - 1.0) * tanHalf, py = (2.0 * (y + 0.5) / side - 1.0) * tanHalf;
      const double along = distance * std::sqrt(1.0 + px * px + py * py);
      for (int c = 0; c < 3; ++c) sum[c] += std::exp(-double(absorption[c]) * along);
    }
  }
  return sum / double(side * side);
}

// The path tracer's image of `scene` (w x h at spp) is the same bytes on one thread
// and on two, another seed gives another, and it is not black.
inline void expectSeedAloneNotThreads(const rt::RtScene& scene, int w, int h, int spp) {
  rt::RenderSettings one = pathSettings(w, h, spp), two = one, other = one;
  one.threads = 1;
  two.threads = 2;
  other.seed = 7;
  const rt::RenderResult a = rt::Integrator(scene, one).render(), b = rt::Integrator(scene, two).render(),
                         c = rt::Integrator(scene, other).render();
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  EXPECT_NE(a.image.pixels, c.image.pixels);
  EXPECT_GT(meanOf(a.image).x, 0.0);
}
