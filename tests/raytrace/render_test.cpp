// Whole renders of analytic scenes whose answer is known (pbrt's habit): a diffuse
// sphere under a point light, the inside of a sphere lit from its centre, mirrors,
// hard shadow edges, planes and spheres far from the origin or at extreme radii, and
// images that are the same bytes whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "raytrace/camera.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/terrain_material.h"
#include "raytrace/tone_map.h"
#include "terrain/materials.h"
#include "test_scenes.h"

namespace {

rt::RenderSettings smallImage(int w, int h, rt::Precision precision = rt::Precision::Float) {
  rt::RenderSettings s;
  s.width = w;
  s.height = h;
  s.precision = precision;
  return s;
}

// The nearest root of |o + t d - c| = r in double, or -1.
double sphereHit(const rt::Ray<double>& ray, glm::dvec3 c, double r) {
  const glm::dvec3 oc = ray.o - c;
  const double b = glm::dot(oc, ray.d), cc = glm::dot(oc, oc) - r * r, disc = b * b - cc;
  if (disc < 0) return -1;
  const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
  return t0 > 0 ? t0 : (t1 > 0 ? t1 : -1);
}

void expectColorNear(glm::vec3 actual, glm::vec3 expected, double tol, const std::string& where) {
  EXPECT_NEAR(actual.r, expected.r, tol) << where;
  EXPECT_NEAR(actual.g, expected.g, tol) << where;
  EXPECT_NEAR(actual.b, expected.b, tol) << where;
}

class RenderTest : public ::testing::TestWithParam<rt::Precision> {};
INSTANTIATE_TEST_SUITE_P(Precisions, RenderTest, ::testing::Values(rt::Precision::Float, rt::Precision::Double),
                         [](const auto& param) { return param.param == rt::Precision::Float ? "Float" : "Double"; });

TEST(Camera, RaysAreTheCourseFormula) {
  CameraDesc c = lookAt({0, 1.5, -3}, {0, 1.5, 1});
  const rt::PinholeCamera camera(c, 320, 240);
  const double yScale = std::tan(M_PI / 6), xScale = yScale * 320.0 / 240.0;
  for (auto [x, y] : {std::pair{0, 0}, {319, 0}, {160, 120}, {17, 203}}) {
    const rt::Ray<double> ray = camera.generateRay<double>(x + 0.5, y + 0.5);
    const glm::dvec3 expected =
        glm::normalize(glm::dvec3((2 * (x + 0.5) / 320 - 1) * xScale, -(2 * (y + 0.5) / 240 - 1) * yScale, 1.0));
    EXPECT_NEAR(ray.d.x, expected.x, 1e-12);
    EXPECT_NEAR(ray.d.y, expected.y, 1e-12);
    EXPECT_NEAR(ray.d.z, expected.z, 1e-12);
    EXPECT_EQ(ray.o, glm::dvec3(0, 1.5, -3));
  }
}

// Primary rays end at the far plane (a view-space depth, so an oblique ray reaches
// farther along itself), as the rasterizer's depth range does.
TEST(Camera, PrimaryRaysEndAtTheFarPlane) {
  CameraDesc c = lookAt({0, 1.5, -3}, {0, 1.5, 1});
  c.farPlane = 10.0;
  const rt::PinholeCamera camera(c, 320, 240);
  for (auto [x, y] : {std::pair{160, 120}, {0, 0}, {319, 17}}) {
    const rt::Ray<double> ray = camera.clippedToFarPlane(camera.generateRay<double>(x + 0.5, y + 0.5));
    const glm::dvec3 end = ray(ray.tMax);
    EXPECT_NEAR(glm::dot(end - ray.o, camera.forward()), 10.0, 1e-9) << x << ", " << y;
  }
  const rt::Ray<float> shorter = camera.clippedToFarPlane(rt::Ray<float>{glm::vec3(0), glm::vec3(0, 0, 1), 4.0f});
  EXPECT_EQ(shorter.tMax, 4.0f);  // a tMax already short of the plane stays
}

// One diffuse sphere under a point light: colour * (ambient + diffuse * max(N.L, 0)),
// with N and L computed here from the analytic hit point; unlit side: ambient only.
TEST_P(RenderTest, DiffuseSphereMatchesTheClosedForm) {
  const glm::dvec3 centre(0.2, 0.1, 4.0), light(-3, 4, 0.5);
  const double radius = 1.3;
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}));
  const glm::vec3 color(0.8f, 0.5f, 0.3f);
  scene.addSphere(centre, radius, scene.addMaterial(classic(color, 0.1f, 0.9f)));
  scene.addLight(pointLight(light));
  const rt::Integrator integrator(scene, smallImage(64, 48, GetParam()));
  const rt::PinholeCamera camera(scene.camera(), 64, 48);
  int lit = 0, unlit = 0, background = 0;
  for (int y = 0; y < 48; y += 3) {
    for (int x = 0; x < 64; x += 3) {
      const auto ray = camera.generateRay<double>(x + 0.5, y + 0.5);
      const double t = sphereHit(ray, centre, radius);
      glm::vec3 expected(0.0f);
      if (t > 0) {
        const glm::dvec3 p = ray(t), n = glm::normalize(p - centre), l = glm::normalize(light - p);
        const double nDotL = std::max(glm::dot(n, l), 0.0);
        expected = color * float(0.1 + 0.9 * nDotL);
        (nDotL > 0 ? lit : unlit)++;
      } else {
        ++background;
      }
      const double tol = GetParam() == rt::Precision::Float ? 1e-4 : 1e-6;
      expectColorNear(integrator.renderPixel(x, y), expected, tol, "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
  }
  EXPECT_GT(lit, 20);
  EXPECT_GT(unlit, 5);
  EXPECT_GT(background, 20);
}

// The inside of a sphere with a point light at its centre: N.L = 1 everywhere (N is
// the inward, viewer-facing normal), so every pixel is colour * (ambient + diffuse),
// also with the whole scene moved 1e5 from the origin: no acne, no hole, no NaN.
TEST_P(RenderTest, InsideASphereLitFromItsCentreIsUniform) {
  for (const glm::dvec3 origin : {glm::dvec3(0), glm::dvec3(1e5, -1e5, 1e5)}) {
    const glm::dvec3 centre = origin + glm::dvec3(0, 1, 2);
    rt::RtScene scene = emptyScene(lookAt(centre + glm::dvec3(0.4, -0.3, -0.5), centre + glm::dvec3(0, 0, 2), 90.0));
    const glm::vec3 color(0.6f, 0.7f, 0.2f);
    scene.addSphere(centre, 2.0, scene.addMaterial(classic(color, 0.25f, 0.75f)));
    scene.addLight(pointLight(centre));
    rt::RenderSettings settings = smallImage(48, 36, GetParam());
    const rt::RenderResult result = rt::Integrator(scene, settings).render();
    int wrong = 0;
    for (const glm::vec3& c : result.image.pixels) {
      if (std::isnan(c.r) || std::abs(c.r - color.r) > 1e-5f || std::abs(c.g - color.g) > 1e-5f ||
          std::abs(c.b - color.b) > 1e-5f) {
        ++wrong;
      }
    }
    EXPECT_EQ(wrong, 0) << "origin " << origin.x;
    EXPECT_EQ(result.rays.primary, 48u * 36u);
    EXPECT_EQ(result.rays.shadow, 48u * 36u);
  }
}

// A mirror plane facing the camera reflects a constant-coloured wall behind it:
// reflection * wall colour; with depth 0 no reflection is traced and it is black.
TEST_P(RenderTest, MirrorReflectsAKnownColour) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 40.0));
  scene.addPlane({0, 0, 5}, {0, 0, -1}, scene.addMaterial(classic(glm::vec3(1), 0.0f, 0.0f, 0.8f)));
  const glm::vec3 wall(0.2f, 0.4f, 0.6f);
  scene.addPlane({0, 0, -5}, {0, 0, 1}, scene.addMaterial(classic(wall, 1.0f, 0.0f)));
  rt::RenderSettings settings = smallImage(8, 6, GetParam());
  expectColorNear(rt::Integrator(scene, settings).renderPixel(3, 2), 0.8f * wall, 1e-6, "depth 5");
  settings.maxDepth = 0;
  expectColorNear(rt::Integrator(scene, settings).renderPixel(3, 2), glm::vec3(0), 0, "depth 0");
}

// Two parallel mirrors (reflection 0.5) that also glow (ambient 1): the sum of
// 0.5^k for k = 0..depth, and exactly `depth` reflection rays per pixel.
TEST_P(RenderTest, MirrorRecursionStopsAtTheMaximumDepth) {
  rt::RtScene scene = emptyScene(lookAt({0, 0, 0}, {0, 0, 1}, 30.0));
  const int m = scene.addMaterial(classic(glm::vec3(1), 1.0f, 0.0f, 0.5f));
  scene.addPlane({0, 0, 3}, {0, 0, -1}, m);
  scene.addPlane({0, 0, -3}, {0, 0, 1}, m);
  for (int depth : {0, 1, 5}) {
    rt::RenderSettings settings = smallImage(8, 6, GetParam());
    settings.maxDepth = depth;
    rt::RayCounters counters;
    const glm::vec3 c = rt::Integrator(scene, settings).renderPixel(4, 3, &counters);
    const float expected = float(2.0 - std::pow(0.5, depth));
    EXPECT_NEAR(c.r, expected, 1e-6) << "depth " << depth;
    EXPECT_EQ(counters.reflection, std::uint64_t(depth));
  }
}

// A sphere between a point light and a floor casts a disc of radius
// d tan(asin(r / h)) (h: light to sphere centre, d: light to floor). Floor points
// 0.2% inside the disc are in shadow, 0.2% outside are lit, all around it.
TEST_P(RenderTest, HardShadowEdgeLandsWhereGeometrySays) {
  rt::RtScene scene = emptyScene(lookAt({0, 1, -6}, {0, 0, 0}));
  const glm::vec3 color(0.5f);
  scene.addPlane({0, 0, 0}, {0, 1, 0}, scene.addMaterial(classic(color, 0.1f, 0.9f)));
  scene.addSphere({0, 2, 0}, 0.5, scene.addMaterial(classic(glm::vec3(1), 0.1f, 0.9f)));
  scene.addLight(pointLight({0, 4, 0}));
  const double radius = 4.0 * std::tan(std::asin(0.5 / 2.0));
  const rt::Integrator integrator(scene, smallImage(8, 8, GetParam()));
  for (int k = 0; k < 36; ++k) {
    const double phi = 2 * M_PI * k / 36;
    for (double f : {0.998, 1.002}) {
      const glm::dvec3 p(f * radius * std::cos(phi), 0.0, f * radius * std::sin(phi));
      const glm::dvec3 eye(0, 1, -6);
      const glm::vec3 c = integrator.traceRay(rt::Ray<double>{eye, p - eye});
      const double nDotL = glm::normalize(glm::dvec3(0, 4, 0) - p).y;
      const float expected = f < 1 ? 0.5f * 0.1f : float(0.5 * (0.1 + 0.9 * nDotL));
      EXPECT_NEAR(c.r, expected, 1e-5) << "phi " << phi << (f < 1 ? " inside" : " outside");
    }
  }
}

// A lit plane seen at grazing and steep angles, at the origin and 1e5 away: every
// pixel that sees it matches the closed form at the analytic hit point (no acne:
// a self-shadowed pixel would drop to ambient), and no pixel is NaN.
TEST_P(RenderTest, PlaneUnderAPointLightHasNoAcneFarFromTheOrigin) {
  for (const glm::dvec3 origin : {glm::dvec3(0), glm::dvec3(1e5, 1e5, -1e5)}) {
    const glm::dvec3 eye = origin + glm::dvec3(0, 1.5, -4), light = origin + glm::dvec3(0.5, 3, 2);
    rt::RtScene scene = emptyScene(lookAt(eye, origin + glm::dvec3(0, 0, 3), 70.0));
    const glm::vec3 color(0.9f, 0.8f, 0.7f);
    scene.addPlane(origin, {0, 1, 0}, scene.addMaterial(classic(color, 0.1f, 0.9f)));
    scene.addLight(pointLight(light));
    const int w = 64, h = 48;
    const rt::RenderResult result = rt::Integrator(scene, smallImage(w, h, GetParam())).render();
    const rt::PinholeCamera camera(scene.camera(), w, h);
    // Float at 1e5 represents positions to 1/128 m, so N.L is off by up to ~0.01.
    const bool coarse = GetParam() == rt::Precision::Float && origin.x != 0;
    const double tol = coarse ? 1e-2 : 1e-4;
    int floorPixels = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const glm::vec3 c = result.image.at(x, y);
        ASSERT_FALSE(std::isnan(c.r + c.g + c.b));
        const auto ray = camera.generateRay<double>(x + 0.5, y + 0.5);
        if (ray.d.y >= 0) {
          EXPECT_EQ(c, glm::vec3(0));
          continue;
        }
        const glm::dvec3 p = ray((origin.y - ray.o.y) / ray.d.y);
        const double nDotL = glm::normalize(light - p).y;
        ++floorPixels;
        EXPECT_NEAR(c.r, color.r * (0.1 + 0.9 * nDotL), tol) << x << "," << y << " origin " << origin.x;
      }
    }
    EXPECT_GT(floorPixels, w * h / 3);
  }
}

// A sphere of radius 1e5 as the ground and one of radius 1e-3 seen up close: both
// shaded as the closed form says, no acne, no NaN.
TEST_P(RenderTest, HugeAndTinySpheresShadeAsTheClosedForm) {
  struct Case {
    glm::dvec3 centre;
    double radius;
    glm::dvec3 eye, light;
    double fovy, tol;
  };
  const bool isFloat = GetParam() == rt::Precision::Float;
  const Case cases[] = {
      // Float positions near the 1e5 sphere's surface are off by ~1e5 ulp (0.008 m).
      {{0, -1e5, 0}, 1e5, {0, 2, -3}, {1, 4, 2}, 70.0, isFloat ? 1e-2 : 1e-5},
      {{0, 0, 0}, 1e-3, {0, 0.001, -0.01}, {0.01, 0.02, -0.005}, 20.0, isFloat ? 1e-3 : 1e-6},
  };
  for (const Case& k : cases) {
    rt::RtScene scene = emptyScene(lookAt(k.eye, k.centre, k.fovy));
    const glm::vec3 color(0.7f);
    scene.addSphere(k.centre, k.radius, scene.addMaterial(classic(color, 0.1f, 0.9f)));
    scene.addLight(pointLight(k.light));
    const int w = 40, h = 30;
    const rt::RenderResult result = rt::Integrator(scene, smallImage(w, h, GetParam())).render();
    const rt::PinholeCamera camera(scene.camera(), w, h);
    int hits = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const glm::vec3 c = result.image.at(x, y);
        ASSERT_FALSE(std::isnan(c.r)) << x << "," << y;
        const auto ray = camera.generateRay<double>(x + 0.5, y + 0.5);
        const double t = sphereHit(ray, k.centre, k.radius);
        if (t < 0) continue;
        ++hits;
        const glm::dvec3 p = ray(t);
        const double nDotL = std::max(glm::dot(glm::normalize(p - k.centre), glm::normalize(k.light - p)), 0.0);
        EXPECT_NEAR(c.r, color.r * (0.1 + 0.9 * nDotL), k.tol) << x << "," << y << " radius " << k.radius;
      }
    }
    EXPECT_GT(hits, w * h / 8) << "radius " << k.radius;
  }
}

rt::RtScene softCornell() {
  rt::RtScene scene = emptyScene(lookAt({0, 1.5, -3}, {0, 1.5, 1}));
  const int white = scene.addMaterial(classic(glm::vec3(0.75f), 0.1f, 0.9f));
  scene.addPlane({0, 0, 0}, {0, 1, 0}, white);
  scene.addPlane({0, 3, 0}, {0, -1, 0}, white);
  scene.addPlane({0, 0, 5}, {0, 0, -1}, white);
  scene.addSphere({-1.2, 0.7, 3.0}, 0.7, white);
  scene.addSphere({0.9, 0.9, 3.4}, 0.9, scene.addMaterial(classic(glm::vec3(1), 0.0f, 0.2f, 0.8f)));
  LightDesc area;
  area.type = LightType::Area;
  area.position = {0, 2.8, 2};
  scene.addLight(area);
  return scene;
}

// Jittered pixel samples and soft-shadow samples: the same seed gives the same
// bytes with one thread and two; another seed gives another image.
TEST(Render, DeterministicWhateverTheThreadCount) {
  const rt::RtScene scene = softCornell();
  rt::RenderSettings settings = smallImage(80, 60);
  settings.samplesPerPixel = 4;
  settings.shadowSamples = 3;
  settings.seed = 1234;
  settings.threads = 1;
  const rt::RenderResult one = rt::Integrator(scene, settings).render();
  settings.threads = 2;
  settings.tileSize = 7;  // other tile shapes too: pixels must not depend on tiles
  const rt::RenderResult two = rt::Integrator(scene, settings).render();
  ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
  EXPECT_EQ(std::memcmp(one.image.pixels.data(), two.image.pixels.data(), one.image.pixels.size() * sizeof(glm::vec3)), 0);
  EXPECT_EQ(one.rays.total(), two.rays.total());
  settings.seed = 99;
  const rt::RenderResult other = rt::Integrator(scene, settings).render();
  EXPECT_NE(std::memcmp(one.image.pixels.data(), other.image.pixels.data(), one.image.pixels.size() * sizeof(glm::vec3)), 0);
}

TEST(Render, ProgressReportsEveryTileAndCanCancel) {
  const rt::RtScene scene = softCornell();
  rt::RenderSettings settings = smallImage(64, 40);  // 4 x 3 tiles of 16
  int calls = 0, last = 0;
  settings.progress = [&](const rt::RenderProgress& p) {
    ++calls;
    last = p.tilesDone;
    EXPECT_EQ(p.tilesTotal, 12);
    EXPECT_GT(p.rays.primary, 0u);
    return true;
  };
  const rt::RenderResult all = rt::Integrator(scene, settings).render();
  EXPECT_EQ(calls, 12);
  EXPECT_EQ(last, 12);
  EXPECT_FALSE(all.cancelled);
  settings.threads = 1;
  settings.progress = [](const rt::RenderProgress& p) { return p.tilesDone < 3; };
  const rt::RenderResult stopped = rt::Integrator(scene, settings).render();
  EXPECT_TRUE(stopped.cancelled);
  EXPECT_LT(stopped.rays.primary, all.rays.primary);
}

// The course's output: clamp to [0, 1], gamma 1/2.2, (int)(v * 255 + 0.5).
TEST(ToneMap, CourseOutputCurve) {
  engine::RenderDesc render;
  render.toneMap = engine::ToneMap::None;
  render.output = engine::OutputCurve::Gamma22;
  rt::Framebuffer fb(4, 1);
  fb.at(0, 0) = glm::vec3(-1.0f, 0.0f, 2.0f);
  fb.at(1, 0) = glm::vec3(0.5f, 0.1f, 1.0f);
  fb.at(2, 0) = glm::vec3(std::nanf(""), 0.0f, 0.0f);
  const engine::Image image = rt::toImage(fb, render);
  EXPECT_EQ(image.at(0, 0)[0], 0);
  EXPECT_EQ(image.at(0, 0)[2], 255);
  EXPECT_EQ(image.at(1, 0)[0], int(std::pow(0.5f, 1 / 2.2f) * 255 + 0.5f));
  EXPECT_EQ(image.at(1, 0)[1], int(std::pow(0.1f, 1 / 2.2f) * 255 + 0.5f));
  EXPECT_EQ(image.at(2, 0)[0], 0);
  EXPECT_EQ(image.at(3, 0)[3], 255);
}

}  // namespace

// The terrain's layered material per hit: the grass layer low on flat ground, rock on
// a cliff, snow high up (brighter, glossier), as terrain.frag blends them.
TEST(TerrainMaterial, LayersFollowHeightAndSlope) {
  rt::RtScene scene;
  MaterialDesc white;
  white.color = glm::vec3(1.0f);
  const int material = scene.addMaterial(white);
  ASSERT_TRUE(scene.setTerrainMaterial(material, rt::RtTerrainMaterial(-50.0, 100.0f)).ok());
  const glm::vec2 uv(0.3f, 0.7f);
  const glm::vec3 up(0, 1, 0), cliff(1, 0, 0);
  const rt::HitMaterial grass = scene.materialAt(material, uv, 0.0f, -50.0, up);
  const rt::HitMaterial rock = scene.materialAt(material, uv, 0.0f, -20.0, cliff);
  const rt::HitMaterial snow = scene.materialAt(material, uv, 0.0f, 50.0, up);
  EXPECT_FLOAT_EQ(grass.roughness, 0.95f);
  EXPECT_FLOAT_EQ(rock.roughness, 0.8f);
  EXPECT_FLOAT_EQ(snow.roughness, 0.5f);
  EXPECT_FLOAT_EQ(grass.specular, 0.02f);
  EXPECT_FLOAT_EQ(snow.specular, 0.25f);
  EXPECT_GT(grass.albedo.g, grass.albedo.r);  // green
  EXPECT_GT(grass.albedo.g, grass.albedo.b);
  EXPECT_GT(snow.albedo.b, 0.5f);             // bright
  EXPECT_GT(snow.albedo.r, rock.albedo.r);
  EXPECT_NEAR(rock.albedo.r, rock.albedo.g, 0.1f);  // grey
  // A plain material is untouched.
  const rt::HitMaterial plain = scene.materialAt(0, uv, 0.0f, 50.0, up);
  EXPECT_EQ(plain.roughness, scene.materials()[0].roughness);
}

// The terrain's material finds each scale's texel taps once and reads them in all its
// layers (RtTexture::taps, read): the layers must be alike, and the blend must be the
// one made of each layer's own sample(), bit for bit, from texel centres and edges
// to coordinates far from zero, at every level of detail and between levels.
TEST(TerrainMaterial, SharedTapsAreEachLayersOwnSamples) {
  const rt::RtTerrainMaterial terrain(-57.0, 140.0f);
  const auto& layers = terrain.layers();
  ASSERT_TRUE(layers[1].tapsLike(layers[0]));
  ASSERT_TRUE(layers[2].tapsLike(layers[0]));
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto coordinate = [&] {
    switch (rng() % 3) {
      case 0: return (unit(rng) - 0.5f) * 64.0f;
      case 1: return float(int(rng() % 4096) - 2048) / 512.0f;  // texel edges and centres of the 256 level
      default: return (unit(rng) - 0.5f) * 2e5f;                 // far from zero
    }
  };
  for (int i = 0; i < 200000; ++i) {
    const glm::vec2 uv(coordinate(), coordinate());
    const float footprint = i % 5 == 0 ? 0.0f : std::ldexp(unit(rng), -int(rng() % 12));
    const double y = -57.0 + 160.0 * double(unit(rng));
    const float normalY = unit(rng);
    const glm::vec2 uvFar = uv * engine::terrain::kLayerFarScale;
    const float footprintFar = footprint * engine::terrain::kLayerFarScale;
    const glm::vec3 grass = layers[0].sample(uv, footprint) * layers[0].sample(uvFar, footprintFar) * 2.0f;
    const glm::vec3 rock = layers[1].sample(uv, footprint) * layers[1].sample(uvFar, footprintFar) * 2.0f;
    const glm::vec3 snow = layers[2].sample(uv, footprint);
    const glm::vec3 w = engine::terrain::layerWeights(float(y + 57.0) / 140.0f, 1.0f - normalY, rock.r * 2.0f - 0.5f);
    const glm::vec3 want = grass * w.x + rock * w.y + snow * w.z;
    const glm::vec3 got = terrain.sample(uv, footprint, y, normalY).albedo;
    ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0)
        << "uv (" << uv.x << ", " << uv.y << ") footprint " << footprint << " y " << y;
  }
}
