// The Whitted tracer's packets (raytrace/whitted_packets.h) against its scalar path:
// Integrator::render() takes the packets where they apply, renderPixel() never does,
// and every pixel must be the same float bits, with the same ray counts. Random rooms
// of spheres and planes (bounded and not, near and far from the origin, tiny and huge),
// classic materials with highlights, mirrors and emission, point lights with and
// without fall-off, suns, area lights of 1 to 4 x 4 shadow rays, fog, a sky or a
// background, every mirror depth and several sample counts, on image sizes that leave
// packets and tiles partly filled.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <random>

#include "asset/scene_file.h"
#include "raytrace/camera_lanes.h"
#include "raytrace/describe.h"
#include "raytrace/integrator.h"
#include "raytrace/rt_scene.h"
#include "raytrace/scene_builder.h"
#include "raytrace/whitted_packets.h"
#include "test_scenes.h"

namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// render() against renderPixel() over the whole image, bit for bit, and the ray counts.
void expectRenderIsRenderPixel(const rt::RtScene& scene, const rt::RenderSettings& settings, const std::string& what) {
  const rt::Integrator integrator(scene, settings);
  const rt::RenderResult image = integrator.render();
  rt::RayCounters scalar;
  int differing = 0;
  for (int y = 0; y < settings.height; ++y) {
    for (int x = 0; x < settings.width; ++x) {
      const glm::vec3 expected = integrator.renderPixel(x, y, &scalar);
      const glm::vec3 actual = image.image.at(x, y);
      if (!sameBits(actual, expected) && ++differing <= 3) {
        ADD_FAILURE() << what << ": pixel " << x << "," << y << " is (" << actual.r << ", " << actual.g << ", "
                      << actual.b << "), the scalar tracer's (" << expected.r << ", " << expected.g << ", "
                      << expected.b << ")";
      }
    }
  }
  EXPECT_EQ(differing, 0) << what;
  EXPECT_EQ(image.rays.primary, scalar.primary) << what;
  EXPECT_EQ(image.rays.shadow, scalar.shadow) << what;
  EXPECT_EQ(image.rays.reflection, scalar.reflection) << what;
}

void expectPacketsAreTheScalarTracer(const rt::RtScene& scene, const rt::RenderSettings& settings,
                                     const std::string& what) {
  ASSERT_TRUE(rt::WhittedPackets::create(scene, settings).has_value()) << what << ": the packets must apply";
  expectRenderIsRenderPixel(scene, settings, what);
}

glm::dvec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
}

// A room: the camera at `origin` plus a few units, shapes around what it looks at.
rt::RtScene randomRoom(std::mt19937& rng, const glm::dvec3& origin) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  const glm::dvec3 eye = origin + glm::dvec3(in(-1, 1), in(0.5, 2), in(-4, -2));
  rt::RtScene scene = emptyScene(lookAt(eye, origin + glm::dvec3(in(-1, 1), in(0, 1.5), in(1, 4)), in(30, 90)));
  if (u(rng) < 0.5) {
    engine::SkyDesc sky;  // the gradient, with the last sun's disk
    scene.setSky(sky);
  }
  if (u(rng) < 0.3) {
    engine::FogDesc fog;
    fog.enabled = true;
    fog.density = float(in(0.01, 0.3));
    scene.setFog(fog);
  }
  const int materials = 6;
  for (int m = 0; m < materials; ++m) {
    MaterialDesc d = classic(glm::vec3(in(0, 1), in(0, 1), in(0, 1)), float(in(0, 0.3)), float(in(0.2, 1)));
    if (u(rng) < 0.4) d.specular = float(in(0.1, 1)), d.shininess = float(in(1, 200));
    if (u(rng) < 0.3) d.reflection = float(in(0.2, 1));
    if (u(rng) < 0.15) d.emission = glm::vec3(float(in(0, 2)), float(in(0, 2)), float(in(0, 2)));
    scene.addMaterial(d);
  }
  const auto material = [&] { return int(u(rng) * materials) + 1; };  // 0 is the default
  const int spheres = 1 + int(u(rng) * 5);
  for (int s = 0; s < spheres; ++s) {
    const double radius = std::pow(10.0, in(-2, 0.5));
    scene.addSphere(origin + glm::dvec3(in(-3, 3), in(0, 3), in(0, 6)), radius, material());
  }
  const int planes = int(u(rng) * 6);
  for (int p = 0; p < planes; ++p) {
    const glm::dvec3 normal = p < 2 ? glm::dvec3(0, p == 0 ? 1 : -1, 0) : randomUnit(rng);
    const glm::dvec3 point = origin + glm::dvec3(in(-3, 3), p == 1 ? 3.5 : in(-0.5, 0.2), in(0, 7));
    scene.addPlane(point, normal, material(), u(rng) < 0.4 ? in(0.5, 4) : 0.0);
  }
  const int lights = 1 + int(u(rng) * 3);
  for (int l = 0; l < lights; ++l) {
    LightDesc light = pointLight(origin + glm::dvec3(in(-2, 2), in(1, 3.4), in(0, 5)));
    if (const double kind = u(rng); kind < 0.25) {
      light.type = LightType::Sun;
      light.direction = randomUnit(rng);
    } else if (kind < 0.5) {  // a rectangle: its shadow rays draw from the pixel's stream
      light.type = LightType::Area;
      light.edgeU = randomUnit(rng) * in(0.1, 2);
      light.edgeV = glm::normalize(glm::cross(light.edgeU, randomUnit(rng))) * in(0.1, 2);
    }
    light.color = glm::vec3(float(in(0.3, 1)), float(in(0.3, 1)), float(in(0.3, 1)));
    light.intensity = float(in(0.5, 3));
    light.falloff = u(rng) < 0.5;
    light.shadows = u(rng) < 0.85;
    scene.addLight(light);
  }
  return scene;
}

TEST(WhittedPackets, RandomRoomsAreTheScalarTracerBitForBit) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the packets need AVX2";
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int sampleCounts[] = {1, 2, 4, 7, 9};
  for (int room = 0; room < 300; ++room) {
    // A third of the rooms far from the origin, where float's rounding is coarse.
    const glm::dvec3 origin = room % 3 == 2 ? glm::dvec3(1e4 * u(rng), -3e3, 2e4 * u(rng)) : glm::dvec3(0.0);
    const rt::RtScene scene = randomRoom(rng, origin);
    rt::RenderSettings settings;
    settings.width = 13 + int(u(rng) * 30);
    settings.height = 7 + int(u(rng) * 20);
    settings.samplesPerPixel = sampleCounts[room % 5];
    settings.maxDepth = room % 7 == 0 ? 0 : 1 + room % 5;
    settings.seed = std::uint64_t(room) * 7919u + 1u;
    settings.tileSize = room % 2 == 0 ? 16 : 5;
    settings.shadowSamples = 1 + room % 4;
    expectPacketsAreTheScalarTracer(scene, settings, "room " + std::to_string(room));
    if (HasFailure()) return;
  }
}

// Many samples a pixel: the lanes' streams stay in step however many there are.
TEST(WhittedPackets, ManySamplesAPixelAreTheScalarTracer) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the packets need AVX2";
  std::mt19937 rng(7);
  for (int spp : {255, 256, 257, 300}) {
    rt::RenderSettings settings;
    settings.width = 9;
    settings.height = 5;
    settings.samplesPerPixel = spp;
    expectPacketsAreTheScalarTracer(randomRoom(rng, glm::dvec3(0.0)), settings, std::to_string(spp) + " spp");
  }
}

// The camera's rays eight at a time (camera_lanes.h: the Whitted packets and the path
// tracer's spans) against PinholeCamera's one at a time, bit for bit: a million image
// points on random cameras, from 1 to 179 degrees, images of 1 to 8192 pixels a
// side, points anywhere in the image and past its edges, cameras looking straight
// up and down, near planes far away.
TEST(CameraLanes, AreTheScalarCameraBitForBit) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the lanes need AVX2";
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  std::uint64_t clipped = 0;
  for (int c = 0; c < 2000; ++c) {
    engine::CameraDesc desc = lookAt(glm::dvec3(u(rng) - 0.5, u(rng), u(rng)) * std::pow(10.0, 5.0 * u(rng)),
                                     glm::dvec3(u(rng), u(rng), u(rng)) * 10.0 - 5.0, 1.0 + 178.0 * u(rng));
    if (c % 10 == 0) desc.forward = glm::dvec3(0, c % 20 == 0 ? 1 : -1, 0), desc.up = glm::dvec3(0, 0, 1);
    desc.farPlane = std::pow(10.0, 4.0 * u(rng) - 1.0);
    const int w = 1 + int(std::pow(8192.0, u(rng))), h = 1 + int(std::pow(8192.0, u(rng)));
    const rt::PinholeCamera camera(desc, w, h);
    double px[500], py[500];
    for (int i = 0; i < 500; ++i) px[i] = (1.2 * u(rng) - 0.1) * w, py[i] = (1.2 * u(rng) - 0.1) * h;
    float dx[500], dy[500], dz[500], tMax[500];
    rt::lanes8::cameraRays(camera, px, py, 500, dx, dy, dz, tMax);
    for (int i = 0; i < 500; ++i) {
      const rt::Ray<float> ray = camera.clippedToFarPlane(camera.generateRay<float>(px[i], py[i]));
      ASSERT_EQ(bits(dx[i]), bits(ray.d.x)) << "camera " << c << " point " << i;
      ASSERT_EQ(bits(dy[i]), bits(ray.d.y)) << "camera " << c << " point " << i;
      ASSERT_EQ(bits(dz[i]), bits(ray.d.z)) << "camera " << c << " point " << i;
      ASSERT_EQ(bits(tMax[i]), bits(ray.tMax)) << "camera " << c << " point " << i;
      clipped += std::isinf(ray.tMax) ? 0 : 1;
    }
  }
  EXPECT_GT(clipped, 900000u);  // nearly every ray ends at the far plane
}

// The course room as the benchmark renders it (issue 14's goal 4), at a smaller size,
// with its point light and with its 1 x 1 area light (4 x 4 shadow rays a hit).
TEST(WhittedPackets, TheCourseRoomIsTheScalarTracerBitForBit) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "the packets need AVX2";
  rt::RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.samplesPerPixel = 4;
  settings.shadowSamples = 4;
  expectPacketsAreTheScalarTracer(sceneFile("cornell.json"), settings, "cornell.json");
  expectPacketsAreTheScalarTracer(sceneFile("cornell_soft.json"), settings, "cornell_soft.json");
}

// What the packets leave to the scalar tracer: meshes, PBR shading, double precision;
// --describe says which path the tracer takes, and why.
TEST(WhittedPackets, LeaveWhatTheyDoNotTraceToTheScalarTracer) {
  rt::RenderSettings settings;
  const rt::RtScene materials = sceneFile("materials.json");
  EXPECT_FALSE(rt::WhittedPackets::create(materials, settings));
  EXPECT_NE(rt::describe(materials, settings).find("packets: none, one sample at a time ("), std::string::npos);
  if (__builtin_cpu_supports("avx2")) {
    // The row's camera rays still find their first hits together (SpanTracer).
    EXPECT_NE(rt::describe(materials, settings).find("; first hits eight camera rays at a time (AVX2)"),
              std::string::npos);
    EXPECT_EQ(rt::WhittedPackets::unsupported(sceneFile("cornell_soft.json"), settings), nullptr);
    EXPECT_NE(rt::describe(sceneFile("cornell.json"), settings).find("packets: eight camera samples"), std::string::npos);
  }
  rt::RenderSettings doubles;
  doubles.precision = rt::Precision::Double;
  EXPECT_FALSE(rt::WhittedPackets::create(sceneFile("cornell.json"), doubles));
  EXPECT_EQ(rt::describe(materials, doubles).find("first hits"), std::string::npos);
  rt::RtScene mesh = emptyScene(lookAt({0, 0, -3}, {0, 0, 0}));
  mesh.addSphere({0, 0, 0}, 1.0, 0);
  rt::RtMesh triangle;
  triangle.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  triangle.indices = {0, 1, 2};
  ASSERT_TRUE(mesh.addMesh(triangle));
  mesh.build();
  EXPECT_FALSE(rt::WhittedPackets::create(mesh, settings));
}

// Scenes the packets leave to the scalar tracer (meshes, textures, PBR, area lights)
// are rendered a row at a time with the camera's rays made eight at once
// (whitted_tracer.cpp's SpanTracer): still renderPixel's bits and ray counts, at sample
// counts whose strata are square, not, and one, on sizes that leave lanes empty.
TEST(SpanTracer, IsTheScalarTracerBitForBit) {
  for (const char* name : {"materials.json", "demo.json", "materials.json + area light"}) {
    const bool area = std::string(name).ends_with("area light");
    rt::RtScene scene = sceneFile(area ? "materials.json" : name);
    if (area) {  // light samples drawn from the pixel's stream between its positions
      engine::LightDesc light;
      light.type = engine::LightType::Area;
      light.position = scene.camera().position + glm::dvec3(0.0, 4.0, 0.0);
      light.edgeU = glm::dvec3(2.0, 0.0, 0.0);
      light.edgeV = glm::dvec3(0.0, 0.0, 2.0);
      scene.addLight(light);
    }
    for (const int spp : {1, 3, 4}) {
      rt::RenderSettings settings;
      settings.width = 45;
      settings.height = 26;
      settings.samplesPerPixel = spp;
      settings.shadowSamples = 2;
      settings.maxDepth = 3;
      expectRenderIsRenderPixel(scene, settings, std::string(name) + " at " + std::to_string(spp) + " spp");
    }
  }
}

// The window's progressive trace takes rows of tiles (Integrator::renderSpanSamples):
// each pixel must be renderPixelSamples' colour, bit for bit, for both tracers, with
// and without the packets, over spans of every length and passes of samples.
TEST(SpanSamples, AreTheirPixelsBitForBit) {
  std::mt19937 rng(5);
  for (const char* name : {"cornell.json", "cornell_soft.json", "materials.json"}) {
    const rt::RtScene scene = sceneFile(name);
    for (const rt::Method method : {rt::Method::Whitted, rt::Method::Path}) {
      rt::RenderSettings settings;
      settings.method = method;
      settings.width = 64;
      settings.height = 36;
      settings.samplesPerPixel = 4;
      const rt::Integrator integrator(scene, settings);
      for (int span = 0; span < 12; ++span) {
        const int x0 = int(rng() % 60), x1 = x0 + 1 + int(rng() % std::uint32_t(64 - x0)), y = int(rng() % 36);
        const int first = method == rt::Method::Path ? int(rng() % 4) : 0, count = 1 + int(rng() % 3);
        std::vector<glm::vec3> row(std::size_t(x1 - x0));
        rt::RayCounters spanRays, pixelRays;
        integrator.renderSpanSamples(x0, x1, y, first, count, row.data(), &spanRays);
        for (int x = x0; x < x1; ++x) {
          const glm::vec3 expected = integrator.renderPixelSamples(x, y, first, count, &pixelRays);
          ASSERT_TRUE(sameBits(row[std::size_t(x - x0)], expected))
              << name << (method == rt::Method::Path ? " path" : " Whitted") << " pixel " << x << "," << y;
        }
        EXPECT_EQ(spanRays.total(), pixelRays.total()) << name;
      }
    }
  }
}

}  // namespace
