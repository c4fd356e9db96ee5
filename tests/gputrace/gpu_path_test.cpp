// The GPU path tracer (shaders/rt/pathtrace.comp) against the CPU's
// (raytrace/path_tracer.cpp), through EGL and OSMesa: the same image of the room of
// support/rt_room.h, in classic shading and in metallic-roughness with every light
// kind, the environment and emitters, judged statistically.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "../support/gl_test.h"
#include "../support/rt_room.h"
#include "../support/rt_textured.h"
#include "gputrace/gpu_tracer.h"
#include "raytrace/integrator.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// How far the GPU's image is from the CPU's of the same seed, against how far the
// CPU's images of two seeds are from each other (the estimator's own noise).
//
// The GPU runs the CPU's algorithm on the CPU's random numbers, so while its
// arithmetic rounds as the CPU's the two images are the same. A GPU whose sin, cos,
// sqrt or division round differently (GLSL allows it) moves a sample's direction in
// its last bits, and a path that then grazes an edge or meets Russian roulette at
// the threshold goes elsewhere: from there on it is another sample of the same
// estimator. Whatever share of the paths diverge:
// - the pixels' differences GPU - CPU have mean 0, so their mean over the image is
//   within a few of its standard errors (sd of the differences / sqrt(pixels)) of 0:
//   a paired test, valid however correlated the two images are, and as sharp as they
//   are alike. 4 standard errors is a 6e-5 chance per channel. Rounding's own
//   systematic part (a GPU's cos a few ulps off in one direction) is below any
//   visible difference, so a gap up to 1e-4 of the image's mean is allowed besides
//   (measured on llvmpipe: 1e-7 of it);
// - at worst every path diverges and the GPU's image is an independent render:
//   RMSE(GPU, CPU) is then RMSE(CPU seed 1, CPU seed 2) in expectation, and 1.2
//   allows for the spread of that RMSE over 14400 pixels with fireflies.
// A missing light or a wrong MIS weight moves the mean by tens of standard errors
// (GpuPath.TheComparisonCatchesAMissingLight; docs/gpu.md, "The path tracer's images", for the weights).
struct PathAgreement {
  bool samePrimaries = false;
  double rmse = 0.0;   // GPU against the CPU, the same seed
  double noise = 0.0;  // the CPU against itself, seeds 1 and 2
  glm::dvec3 cpuMean{0.0};
  glm::dvec3 meanGap{0.0};    // GPU - CPU, per channel
  glm::dvec3 gapError{0.0};   // the standard error of meanGap
  int identicalPixels = 0;
  double maxError = 0.0;

  bool meansAgree() const {
    for (int c = 0; c < 3; ++c) {
      if (!(std::abs(meanGap[c]) <= 4.0 * gapError[c] + 1e-4 * std::abs(cpuMean[c]))) return false;
    }
    return true;
  }
  bool agrees() const { return samePrimaries && rmse <= 1.2 * noise && meansAgree(); }
};

PathAgreement comparePaths(const rt::RenderResult& gpu, const rt::RenderResult& cpu, const rt::RenderResult& cpuOtherSeed) {
  PathAgreement a;
  a.samePrimaries = gpu.rays.primary == cpu.rays.primary;
  const std::size_t n = cpu.image.pixels.size();
  double noiseSquares = 0.0;
  glm::dvec3 cpuSum(0.0), gapSum(0.0), gapSquares(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 g(gpu.image.pixels[i]), c(cpu.image.pixels[i]), c2(cpuOtherSeed.image.pixels[i]);
    const glm::dvec3 e = g - c, s = c - c2;
    noiseSquares += glm::dot(s, s);
    cpuSum += c;
    gapSum += e;
    gapSquares += e * e;
    a.identicalPixels += gpu.image.pixels[i] == cpu.image.pixels[i] ? 1 : 0;
    a.maxError = std::max({a.maxError, std::abs(e.x), std::abs(e.y), std::abs(e.z)});
  }
  const double count = double(n);
  a.rmse = std::sqrt((gapSquares.x + gapSquares.y + gapSquares.z) / (3.0 * count));
  a.noise = std::sqrt(noiseSquares / (3.0 * count));
  a.cpuMean = cpuSum / count;
  a.meanGap = gapSum / count;
  a.gapError = glm::sqrt(glm::max(gapSquares / count - a.meanGap * a.meanGap, glm::dvec3(0.0)) / (count - 1.0));
  return a;
}

rt::RenderSettings pathSettings() {
  rt::RenderSettings settings;
  settings.method = rt::Method::Path;
  settings.width = 160;
  settings.height = 90;
  settings.samplesPerPixel = 4;
  settings.maxDepth = 16;  // demo's --mode pathtrace default
  return settings;
}

// The GPU's render of `drawn` against the CPU's of `truth` (the same scene but in
// the negative test) with seeds 1 and 2.
PathAgreement gpuAgainstCpu(const rt::RtScene& drawn, const rt::RtScene& truth, const char* what) {
  rt::RenderSettings settings = pathSettings();
  EXPECT_EQ(gpurt::unsupported(drawn, settings), "");
  auto tracer = gpurt::GpuTracer::create(drawn, test::shaderDir());
  EXPECT_TRUE(tracer) << tracer.error().message;
  if (!tracer) return {};
  auto gpu = tracer->render(settings);
  EXPECT_TRUE(gpu) << gpu.error().message;
  if (!gpu) return {};
  const rt::RenderResult cpu = rt::Integrator(truth, settings).render();
  settings.seed = 2;
  const rt::RenderResult cpu2 = rt::Integrator(truth, settings).render();
  const PathAgreement a = comparePaths(*gpu, cpu, cpu2);
  std::printf("gpu path, %s: RMSE %.3g against the CPU's noise %.3g (ratio %.3g); mean %.3g %.3g %.3g, gap %.3g %.3g "
              "%.3g, standard error %.3g %.3g %.3g; %d of %zu pixels identical, max error %.3g; rays GPU "
              "%llu/%llu/%llu, CPU %llu/%llu/%llu (%.2f s)\n",
              what, a.rmse, a.noise, a.noise > 0.0 ? a.rmse / a.noise : 0.0, a.cpuMean.x, a.cpuMean.y, a.cpuMean.z,
              a.meanGap.x, a.meanGap.y, a.meanGap.z, a.gapError.x, a.gapError.y, a.gapError.z, a.identicalPixels,
              cpu.image.pixels.size(),
              a.maxError, (unsigned long long)gpu->rays.primary, (unsigned long long)gpu->rays.shadow,
              (unsigned long long)gpu->rays.reflection, (unsigned long long)cpu.rays.primary,
              (unsigned long long)cpu.rays.shadow, (unsigned long long)cpu.rays.reflection, gpu->seconds);
  return a;
}

// The classic room lit through its open front as well: a grey background (the
// environment as a constant, sampled through its distribution), a sun 2 degrees
// over the horizon straight in (a delta), and a highlight on the white walls (the
// classic lobe drawn by reflectionSample, not lambertSample).
rt::RtScene classicRoomOpenToTheFront() {
  LightDesc sun;
  sun.direction = glm::normalize(glm::dvec3(0.0, 0.03, -1.0));
  sun.intensity = 0.8f;
  sun.color = glm::vec3(1.0f, 0.9f, 0.8f);
  return test::roomWithMeshes(
      [](SceneDesc& desc) {
        desc.sky.enabled = false;
        desc.sky.background = glm::vec3(0.35f, 0.35f, 0.45f);
        desc.materials[0].specular = 0.4f;  // white
        desc.materials[0].shininess = 20.0f;
      },
      sun);
}

// The GPU's path-traced image of `scene` against the CPU's (gpuAgainstCpu's limits).
void expectAgreement(const rt::RtScene& scene, const char* what) {
  SCOPED_TRACE(what);
  const PathAgreement a = gpuAgainstCpu(scene, scene, what);
  EXPECT_TRUE(a.samePrimaries);
  EXPECT_GT(a.noise, 0.0);
  EXPECT_LE(a.rmse, 1.2 * a.noise);
  EXPECT_TRUE(a.meansAgree()) << "mean gap " << a.meanGap.x << " " << a.meanGap.y << " " << a.meanGap.z;
}

class GpuPath : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(GpuPath);

// 160 x 90, 4 samples per pixel, up to 16 bounces: the room with its area light,
// point light, sun, mirror, box and smooth patch on the black background in the
// course's classic shading (Lambert and the mirror), classicRoomOpenToTheFront(), then
// pbrRoom(). Measured on
// llvmpipe: the same ray counts (shadow and bounce rays too), RMSE 1e-5, 2e-5 and
// 3e-6 of the seed-to-seed noise, 83 %, 78 % and 11 % of the pixels the same bits, the
// rest off in the last bits (docs/gpu.md, "The path tracer's images").
TEST_P(GpuPath, RendersTheCpusImageOfTheRoom) {
  for (const int variant : {0, 1, 2}) {
    const char* names[] = {"classic room", "classic room open to the front", "pbr room"};
    const rt::RtScene scene = variant == 0 ? test::roomWithMeshes() : variant == 1 ? classicRoomOpenToTheFront() : test::pbrRoom();
    expectAgreement(scene, names[variant]);
  }
}

// Textures sampled through the ray cone, MASK's cut-outs and single-sided faces
// passed, BLEND as stochastic transparency (a draw from the path's stream where 0 <
// alpha < 1, as the CPU draws it) and its share in shadow rays, the terrain's layers:
// support/rt_textured.h's room (with vertex colours) in classic shading, then in PBR
// under the gradient sky and under an image sky (sampled through its distribution); and the shipped scenes that use them (materials.json, terrain.json); judged
// as the room above. Measured on llvmpipe: the same ray counts and images equal to
// the last bits (docs/gpu.md).
TEST_P(GpuPath, RendersTheCpusImageOfTexturedSurfaces) {
  rt::RtScene room = test::texturedRoom();
  expectAgreement(room, "textured room, classic");
  RenderDesc render = room.render();
  render.shading = Shading::Pbr;
  room.setRender(render);
  room.setSky(SkyDesc{});
  expectAgreement(room, "textured room, pbr, sky");
  const std::filesystem::path file = test::temporaryFile("gpu_path_sky.hdr");
  room.setEnvironment(test::hashedSky(file));
  std::filesystem::remove(file);
  expectAgreement(room, "textured room, pbr, image sky");
}

// Spot lights (common/spot_cone.glsl): pbrRoom with test::addSpots's soft and sharp
// cones, judged as the room above.
TEST_P(GpuPath, RendersTheCpusImageOfSpotLights) {
  rt::RtScene scene = test::pbrRoom();
  test::addSpots(scene);
  expectAgreement(scene, "pbr room under spots");
}

TEST_P(GpuPath, RendersTheCpusImageOfTheShippedTexturedScenes) {
  for (const char* file : {"materials.json", "terrain.json"}) expectAgreement(test::shippedScene(file).scene(), file);
}

// Many samples go in batches of at most 16, a dispatch each, each adding to the sums
// of the ones before: samples [3, 23) of the classic room (batches of 16 and 4) are
// the CPU's samples [3, 23).
TEST_P(GpuPath, SamplesInBatchesAreTheCpusSamples) {
  const rt::RtScene scene = test::roomWithMeshes();
  rt::RenderSettings settings = pathSettings();
  settings.width = 48;
  settings.height = 27;
  settings.firstSample = 3;
  settings.samplesPerPixel = 20;
  auto tracer = gpurt::GpuTracer::create(scene, test::shaderDir());
  ASSERT_TRUE(tracer) << tracer.error().message;
  auto gpu = tracer->render(settings);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const rt::RenderResult cpu = rt::Integrator(scene, settings).render();
  settings.seed = 2;
  const rt::RenderResult cpu2 = rt::Integrator(scene, settings).render();
  const PathAgreement a = comparePaths(*gpu, cpu, cpu2);
  EXPECT_TRUE(a.agrees()) << "RMSE " << a.rmse << " against " << a.noise << ", mean gap " << a.meanGap.x;
  EXPECT_EQ(gpu->rays.primary, 48u * 27u * 20u);
  std::printf("gpu path, 20 samples from the 4th in two batches: RMSE %.3g against the CPU's noise %.3g; %d of %zu "
              "pixels identical; rays GPU %llu/%llu/%llu, CPU %llu/%llu/%llu\n",
              a.rmse, a.noise, a.identicalPixels, cpu.image.pixels.size(), (unsigned long long)gpu->rays.primary,
              (unsigned long long)gpu->rays.shadow, (unsigned long long)gpu->rays.reflection,
              (unsigned long long)cpu.rays.primary, (unsigned long long)cpu.rays.shadow,
              (unsigned long long)cpu.rays.reflection);
}

// glTF's clear coat (smooth over a rough metal, and half a coat over the red wall),
// sheen (under that coat: its albedo table read as the CPU reads it, the base dimmed
// by its scaling, its lobe sampled), thin film (the white walls and the mirror) and
// transmission into an absorbing volume (the blue sphere and box: refraction, total
// internal reflection, Beer-Lambert along the path inside), in the PBR room, judged
// as the rooms above (GpuBsdf checks the lobes one by one).
TEST_P(GpuPath, RendersTheCpusImageOfLayeredMaterials) {
  const rt::RtScene scene = test::pbrRoom(1.5f, test::layeredMaterials);
  expectAgreement(scene, "pbr room, coat, sheen, film, volume");
  // Anisotropy, oriented by a triangle's uv gradient.
  const rt::RtScene brushed = test::brushedMetalRoom();
  expectAgreement(brushed, "textured room, pbr, anisotropic metal");
  // A texture in every layer slot the tracers read (support/rt_textured.h).
  expectAgreement(test::layerTexturedRoom(), "pbr room, layer textures");
  expectAgreement(test::brushedMetalRoom(true), "textured room, pbr, anisotropy texture");
}

// The comparison is not blind: the GPU drawing the open room without its sun fails it.
TEST_P(GpuPath, TheComparisonCatchesAMissingLight) {
  const PathAgreement a = gpuAgainstCpu(test::pbrRoom(0.0f), test::pbrRoom(), "pbr room, the GPU without the sun");
  EXPECT_FALSE(a.agrees());
  EXPECT_FALSE(a.meansAgree());
}

// Both GPU integrators draw every glTF layer (KHR_materials_ior and _specular: the
// dielectric's f0 and f90; _clearcoat, _sheen, _iridescence, _transmission, _volume,
// _anisotropy), with their textures; what they do not draw is refused in one line.
TEST(GpuPathSupport, DrawsEveryLayerAndRefusesInOneLine) {
  rt::RenderSettings path = pathSettings(), whitted;
  const rt::RtScene layered = test::pbrRoom(1.5f, [](SceneDesc& desc) {
    test::layeredMaterials(desc);
    desc.materials[5].layers.specular = 0.5f;
    desc.materials[0].layers.anisotropy = 0.5f;
  });
  EXPECT_EQ(gpurt::unsupported(layered, path), "");
  EXPECT_EQ(gpurt::unsupported(layered, whitted), "");
  const rt::RtScene textured = test::layerTexturedRoom();
  EXPECT_EQ(gpurt::unsupported(textured, path), "");
  EXPECT_EQ(gpurt::unsupported(textured, whitted), "");
  // Media are the CPU path tracer's; the Whitted tracer draws the fog's stand-in.
  rt::RtScene air = layered;
  AtmosphereDesc atmosphere;
  atmosphere.enabled = true;
  air.setAtmosphere(atmosphere);
  EXPECT_EQ(gpurt::unsupported(air, path), "an atmosphere and boxes of fog are not supported (the CPU path tracer renders them)");
  EXPECT_EQ(gpurt::unsupported(air, whitted), "");
  rt::RtScene boxed = layered;
  boxed.setMedia({MediumDesc{}});
  EXPECT_EQ(gpurt::unsupported(boxed, path), "an atmosphere and boxes of fog are not supported (the CPU path tracer renders them)");
  path.precision = rt::Precision::Double;
  EXPECT_EQ(gpurt::unsupported(layered, path), "double precision is not supported");
}

}  // namespace
