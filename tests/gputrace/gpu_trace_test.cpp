// The GPU tracer (engine/gputrace, shaders/rt/) against its CPU twin, through EGL and
// OSMesa: ray queries on the flattened BVH8 find the CPU BVH's closest hits and any
// hits, and the Whitted integrator renders the CPU's image of the course room.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <limits>

#include "../support/gl_test.h"
#include "../support/rt_queries.h"
#include "../support/rt_room.h"
#include "../support/rt_textured.h"
#include "asset/scene_file.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/integrator.h"
#include "raytrace/tone_map.h"

using namespace engine;
using engine::test::GlTest;

namespace {

std::vector<gpurt::RayQuery> queriesOf(const std::vector<rt::Ray<float>>& rays) {
  std::vector<gpurt::RayQuery> out;
  for (const rt::Ray<float>& r : rays) out.push_back(gpurt::RayQuery{glm::vec4(r.o, r.tMax), glm::vec4(r.d, 0.0f)});
  return out;
}

// The GPU's t may differ from the CPU's by its own rounding of division and square
// root (GLSL allows 2.5 ulps for a division, more for sqrt), through a few
// operations: 1e-5 relative is some 80 ulps, far below any distance between two
// different surfaces a ray could hit instead, which would show as a different id.
constexpr float kRelativeT = 1e-5f;

struct Agreement {
  int rays = 0, hits = 0, mismatches = 0, anyMismatches = 0, ties = 0;
  float worstT = 0.0f;
};

Agreement compare(const rt::RtScene& scene, const std::vector<rt::Ray<float>>& rays, int width = 8) {
  const rt::GpuSceneLayout layout = rt::flattenScene(scene);
  auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir(), width);
  EXPECT_TRUE(tracer) << tracer.error().message;
  if (!tracer) return {};
  const std::vector<gpurt::RayAnswer> answers = tracer->trace(queriesOf(rays));
  Agreement a;
  a.rays = int(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const test::ReferenceHit cpu = test::cpuClosestHit(scene, layout, rays[i]);
    const gpurt::RayAnswer& gpu = answers[i];
    a.hits += cpu.kind != 0 ? 1 : 0;
    if (bool(gpu.anyHit) != scene.intersectAny(rays[i])) ++a.anyMismatches;
    if (int(gpu.kind) != cpu.kind) {
      ++a.mismatches;
      continue;
    }
    if (cpu.kind == 0) continue;
    const float error = std::abs(gpu.t - cpu.t) / cpu.t;
    a.worstT = std::max(a.worstT, error);
    // Two triangles meeting where the ray hits: either may win (rt_queries.h, hitsAt).
    const bool tie = cpu.kind == 3 && gpu.index != cpu.index && error <= kRelativeT && test::hitsAt(layout, gpu.index, rays[i], gpu.t);
    a.ties += tie ? 1 : 0;
    if (error > kRelativeT || (gpu.index != cpu.index && !tie)) ++a.mismatches;
  }
  return a;
}

class GpuTrace : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuTrace);

// Both layouts: the CPU's 8-wide nodes, and the 4-wide tree made from them.
TEST_P(GpuTrace, HitsEqualTheCpuBvhsOnAMeshScene) {
  const rt::RtScene scene = test::meshScene();
  for (const int width : {8, 4}) {
    SCOPED_TRACE(width);
    const Agreement a = compare(scene, test::queryRays(4000, 7.0f, 9), width);
    EXPECT_EQ(a.mismatches, 0) << "of " << a.rays;
    EXPECT_EQ(a.anyMismatches, 0);
    EXPECT_GT(a.hits, a.rays / 2);
    std::printf("gpu trace, mesh scene, %d wide: %d rays, %d hits, %d ties at shared edges, worst relative t %.3g\n", width,
                a.rays, a.hits, a.ties, double(a.worstT));
  }
}

// The course room: spheres and planes, rays from inside it in every direction.
TEST_P(GpuTrace, HitsEqualTheCpusInTheCornellRoom) {
  const rt::RtScene scene = test::cornellScene();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> x(-2.4f, 2.4f), y(0.1f, 2.9f), z(-2.9f, 4.9f), dir(-1.0f, 1.0f);
  std::vector<rt::Ray<float>> rays;
  for (int i = 0; i < 4000; ++i) rays.push_back(rt::Ray<float>{{x(rng), y(rng), z(rng)}, {dir(rng), dir(rng), dir(rng)}});
  const Agreement a = compare(scene, rays);
  EXPECT_EQ(a.mismatches, 0) << "of " << a.rays;
  EXPECT_EQ(a.anyMismatches, 0);
  std::printf("gpu trace, cornell: %d rays, %d hits, worst relative t %.3g\n", a.rays, a.hits, double(a.worstT));
}

struct ImageAgreement {
  double meanError = 0.0;  // mean absolute difference of linear channels
  float maxError = 0.0f;
  int differingPixels = 0;  // some 8-bit channel off by more than one level
};

ImageAgreement compareImages(const rt::Framebuffer& cpu, const rt::Framebuffer& gpu, const RenderDesc& render) {
  ImageAgreement a;
  const Image cpu8 = rt::toImage(cpu, render), gpu8 = rt::toImage(gpu, render);
  for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
    bool differs = false;
    for (int c = 0; c < 3; ++c) {
      const float e = std::abs(cpu.pixels[i][c] - gpu.pixels[i][c]);
      a.meanError += double(e);
      a.maxError = std::max(a.maxError, e);
      differs |= std::abs(int(cpu8.pixels[4 * i + std::size_t(c)]) - int(gpu8.pixels[4 * i + std::size_t(c)])) > 1;
    }
    a.differingPixels += differs ? 1 : 0;
  }
  a.meanError /= double(3 * cpu.pixels.size());
  return a;
}

class GpuWhitted : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(GpuWhitted);

// The GPU's Whitted image of `scene` against the CPU's: the same ray counts (within
// 0.1 % for shadow and mirror rays, which a last-bit difference may add or remove),
// mean error and pixels off by more than one level within the limits above.
void expectCpusImage(const gpurt::GpuTracer& tracer, const rt::RtScene& scene, const rt::RenderSettings& settings,
                     const char* what) {
  SCOPED_TRACE(what);
  auto gpu = tracer.render(settings);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const rt::RenderResult cpu = rt::Integrator(scene, settings).render();
  EXPECT_EQ(gpu->rays.primary, cpu.rays.primary);
  EXPECT_NEAR(double(gpu->rays.shadow), double(cpu.rays.shadow), 0.001 * double(cpu.rays.shadow));
  EXPECT_NEAR(double(gpu->rays.reflection), double(cpu.rays.reflection), 0.001 * double(cpu.rays.reflection));
  const ImageAgreement a = compareImages(cpu.image, gpu->image, scene.render());
  EXPECT_LE(a.meanError, 1e-4);
  EXPECT_LE(a.differingPixels, int(0.005 * double(cpu.image.pixels.size())));
  std::printf("gpu whitted, %s: mean error %.3g, max %.3g, %d pixels off by more than one level (%.2f s)\n", what,
              a.meanError, double(a.maxError), a.differingPixels, gpu->seconds);
}

// One tracer for `scene` (llvmpipe compiles its kernel once), its image against the
// CPU's as the scene is, then, given `toPbr`, in PBR shading after `toPbr` edits it.
void expectCpusImages(rt::RtScene scene, const rt::RenderSettings& settings, const std::string& name,
                      const std::function<void(rt::RtScene&)>& toPbr = {}) {
  ASSERT_EQ(gpurt::unsupported(scene, settings), "") << name;
  auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir());
  ASSERT_TRUE(tracer) << tracer.error().message;
  expectCpusImage(*tracer, scene, settings, (name + (toPbr ? ", classic" : "")).c_str());
  if (!toPbr) return;
  RenderDesc render = scene.render();
  render.shading = Shading::Pbr;
  scene.setRender(render);
  toPbr(scene);
  expectCpusImage(*tracer, scene, settings, (name + ", pbr").c_str());
}

rt::RenderSettings whittedSettings() {
  rt::RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.samplesPerPixel = 2;
  settings.shadowSamples = 2;
  return settings;
}

// The same image as the CPU's Whitted tracer at 160 x 90: the room of
// support/rt_room.h with its
// area light (2 x 2 jittered shadow rays), point light, sun, mirror sphere, box and
// smooth patch, two jittered samples per pixel (the per-pixel random streams must
// agree); in the course's classic shading on a black background, then in PBR with
// fog and the gradient sky (its sun disk) seen in the mirror. One tracer per
// backend: llvmpipe compiles the kernel in 1-3 s without a shader cache.
// The GPU's sqrt and division may round differently from the CPU's (GLSL allows a
// few ulps), which moves a hit or a shadow ray's end in the last bits: that changes a
// pixel visibly only where a ray grazes a silhouette or a shadow ray grazes an
// occluder, a few pixels along edges. Hence: mean linear error below 1e-4 (a
// hundredth of an 8-bit level), and at most 0.5 % of the pixels (72) more than one
// level off. llvmpipe rounds as the CPU does: errors of 1e-7 and no pixel off.
TEST_P(GpuWhitted, RendersTheCpusImageOfTheRoom) {
  rt::RtScene scene = test::roomWithMeshes();
  ASSERT_GT(scene.triangleCount(), 12u);
  expectCpusImages(scene, whittedSettings(), "the room", [](rt::RtScene& pbr) {
    pbr.setFog(FogDesc{true, 0.08f, glm::vec3(0.5f, 0.6f, 0.7f)});
    pbr.setSky(SkyDesc{});
  });
}

// Spot lights (common/spot_cone.glsl): the room with test::addSpots's soft and sharp
// cones, in both shadings, with the limits above. Outside a cone no shadow ray is
// traced, on either side.
TEST_P(GpuWhitted, RendersTheCpusImageOfSpotLights) {
  rt::RtScene scene = test::roomWithMeshes();
  test::addSpots(scene);
  expectCpusImages(scene, whittedSettings(), "the room under spots", [](rt::RtScene& pbr) { pbr.setSky(SkyDesc{}); });
}

// Textures sampled as the CPU samples them (support/rt_textured.h: every wrap mode,
// a transformed second uv set, mipmaps picked by the ray cone through a mirror,
// base colour, emissive and metallic-roughness maps, MASK and BLEND from a texture's
// alpha, a single-sided face from behind, the terrain's layers), in both shadings,
// with the same limits: llvmpipe gives the same bytes (GLSL's log2, acos and atan
// may round otherwise elsewhere: a mipmap blend or a sphere's uv a few ulps off).
TEST_P(GpuWhitted, RendersTheCpusImageOfTexturedSurfaces) {
  expectCpusImages(test::texturedRoom(), whittedSettings(), "the textured room", [](rt::RtScene&) {});
}

// An image sky (support/rt_textured.h's hashedSky: a Radiance file, an intensity, a
// turn) over the room without its walls and ceiling (the floor a 6 m square), seen
// directly and in the mirror, both shadings.
TEST_P(GpuWhitted, RendersTheCpusImageOfAnImageSky) {
  rt::RtScene scene = test::roomWithMeshes([](SceneDesc& desc) {
    std::erase_if(desc.primitives, [](const PrimitiveDesc& p) { return p.type == PrimitiveType::Plane && p.point.y != 0.0; });
    for (PrimitiveDesc& p : desc.primitives) {
      if (p.type == PrimitiveType::Plane) p.extent = 3.0;
    }
  });
  const std::filesystem::path file = test::temporaryFile("gpu_whitted_sky.hdr");
  scene.setEnvironment(test::hashedSky(file));
  std::filesystem::remove(file);
  expectCpusImages(scene, whittedSettings(), "the room under an image sky", [](rt::RtScene&) {});
}

// The shipped scenes that use them: materials.json (the glTF material model:
// textures, MASK, BLEND, single-sided quads, an emissive panel, the checkered
// ground) and terrain.json (the terrain's layers, far and near).
TEST_P(GpuWhitted, RendersTheCpusImageOfTheShippedTexturedScenes) {
  for (const char* file : {"materials.json", "terrain.json"}) {
    rt::RenderSettings settings = whittedSettings();
    settings.samplesPerPixel = 1;
    expectCpusImages(test::shippedScene(file).scene(), settings, file);
  }
}

// A window traces a pass a band of rows at a time (GpuTracer::render's rows): bands
// of 7 rows (not the kernels' 8-row groups) over the room, Whitted and path
// traced, are the whole image's rows bit for bit, with the same ray counts in sum.
TEST_P(GpuWhitted, BandsOfRowsAreTheWholeImagesRows) {
  const rt::RtScene scene = test::roomWithMeshes();
  auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir());
  ASSERT_TRUE(tracer) << tracer.error().message;
  rt::RenderSettings settings = whittedSettings();
  settings.width = 40;
  settings.height = 30;
  for (const rt::Method method : {rt::Method::Whitted, rt::Method::Path}) {
    settings.method = method;
    auto whole = tracer->render(settings);
    ASSERT_TRUE(whole) << whole.error().message;
    rt::RayCounters rays;
    int differing = 0;
    for (int row = 0; row < settings.height; row += 7) {
      const int rows = std::min(7, settings.height - row);
      auto band = tracer->render(settings, row, rows);
      ASSERT_TRUE(band) << band.error().message;
      ASSERT_EQ(band->image.height, rows);
      rays += band->rays;
      for (int y = 0; y < rows; ++y) {
        for (int x = 0; x < settings.width; ++x) differing += band->image.at(x, y) != whole->image.at(x, row + y) ? 1 : 0;
      }
    }
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(rays.primary, whole->rays.primary);
    EXPECT_EQ(rays.shadow, whole->rays.shadow);
    EXPECT_EQ(rays.reflection, whole->rays.reflection);
  }
  EXPECT_FALSE(tracer->render(settings, 25, 6));  // past the image: an error, not a crash
}

// glTF's layers as the CPU's Whitted tracer draws them (core/brdf.h's layeredBrdf per
// light, the hemisphere ambient through the layers, one refracted ray through
// KHR_materials_transmission, absorbed inside KHR_materials_volume): support/rt_room.h's
// layered PBR room (a clear coat over a rough metal and over a sheen, a thin film on
// the walls and the mirror, a tinted volume whose rays refract in and out and reflect
// past the critical angle, beside mirror rays: a tree of rays, not a chain), then
// the textured room's brushed metal (anisotropy oriented by the uv gradient), then
// both with a texture in every layer slot the tracers read (support/rt_textured.h),
// with the room's limits.
TEST_P(GpuWhitted, RendersTheCpusImageOfLayeredMaterials) {
  const auto alsoAMirror = [](SceneDesc& desc) { desc.materials[5].reflection = 0.25f; };  // the volume
  expectCpusImages(test::pbrRoom(1.5f, [&](SceneDesc& desc) {
                     test::layeredMaterials(desc);
                     alsoAMirror(desc);
                   }),
                   whittedSettings(), "the layered pbr room");
  expectCpusImages(test::brushedMetalRoom(), whittedSettings(), "the brushed metal");
  expectCpusImages(test::layerTexturedRoom(alsoAMirror), whittedSettings(), "the layered pbr room, textured");
  expectCpusImages(test::brushedMetalRoom(true), whittedSettings(), "the brushed metal, textured");
}

}  // namespace
