// The terrain renderer against a real offscreen context: it builds, draws a
// selection without GL errors and gives a plausible picture (ground, not sky
// everywhere, and not one flat colour); a 16 km field at a demanding target fits
// the GPU page budget without leaving patches out.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "core/image.h"

#include "../support/gl_test.h"
#include "gl/resources.h"
#include "render/frame_block.h"
#include "terrain/lod.h"
#include "terrain/terrain_renderer.h"
#include "terrain_support.h"

using namespace engine;
using namespace engine::terrain;
using engine::test::GlTest;

class TerrainGl : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(TerrainGl);

namespace {

// The frame block the scene renderer fills: a sun, sky ambient and fog.
gl::Buffer bindFrame(const glm::mat4& viewProjection) {
  FrameBlock frame;
  frame.u_viewProjection = viewProjection;
  frame.u_sunDirection = glm::vec4(glm::normalize(glm::vec3(0.5f, 0.8f, 0.3f)), 1.0f);
  frame.u_sunColor = glm::vec4(1.3f, 1.22f, 1.1f, 0.0f);
  frame.u_ambientSky = glm::vec4(0.22f, 0.28f, 0.38f, 0.3f);
  frame.u_ambientGround = glm::vec4(0.1f, 0.09f, 0.07f, 0.0f);
  gl::Buffer ubo = gl::Buffer::create(sizeof(FrameBlock), &frame);
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlockBinding, ubo.id());
  return ubo;
}

struct Target {
  gl::Texture color;
  gl::Renderbuffer depth;
  gl::Framebuffer fb;
};

Target makeTarget(int w, int h) {
  Target t{gl::Texture::create2D(GL_SRGB8_ALPHA8, w, h), gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h),
           gl::Framebuffer::create()};
  t.fb.attach(GL_COLOR_ATTACHMENT0, t.color);
  t.fb.attach(GL_DEPTH_ATTACHMENT, t.depth);
  t.fb.bind();
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glEnable(GL_FRAMEBUFFER_SRGB);
  const float sky[4] = {0.6f, 0.7f, 0.85f, 1.0f};
  glClearBufferfv(GL_COLOR, 0, sky);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
  return t;
}

}  // namespace

TEST_P(TerrainGl, DrawsAPlausibleLandscapeFarFromTheOrigin) {
  const int w = 160, h = 90;
  Target target = makeTarget(w, h);
  ASSERT_TRUE(target.fb.complete());

  TerrainSettings settings = engine::terrain::test::noiseSettings(4096.0, 600.0, {5.0e6, 100.0, -7.0e6});
  auto terrain = Terrain::create(settings);
  ASSERT_TRUE(terrain.ok()) << terrain.error().message;
  auto renderer = TerrainRenderer::create(engine::test::shaderDir(), *terrain);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;

  const glm::dvec3 o = settings.origin;
  const glm::dvec3 eye(o.x + 1000.0, terrain->heightAt(o.x + 1000.0, o.z + 1000.0) + 150.0, o.z + 1000.0);
  const LodCamera camera = engine::terrain::test::makeCamera(eye, eye + glm::dvec3(1.0, -0.25, 1.0), w, h);
  const LodSelection selection = selectLod(*terrain, camera, 2.0);

  const gl::Buffer frame = bindFrame(camera.viewProjection);
  const TerrainDrawStats stats = renderer->draw(selection, eye, nullptr);
  EXPECT_EQ(stats.patchesSkipped, 0u);
  EXPECT_GT(stats.patchesDrawn, 0u);
  EXPECT_EQ(stats.trianglesDrawn, selection.stats.triangles);

  std::vector<std::uint8_t> pixels(std::size_t(w) * h * 4);
  glGetTextureImage(target.color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
  std::size_t skyPixels = 0;
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < pixels.size(); i += 4) {
    const std::uint32_t c = pixels[i] | pixels[i + 1] << 8 | pixels[i + 2] << 16;
    colours.insert(c);
    // The clear colour in sRGB: about (203, 219, 238).
    if (std::abs(int(pixels[i]) - 203) <= 2 && std::abs(int(pixels[i + 1]) - 219) <= 2 &&
        std::abs(int(pixels[i + 2]) - 238) <= 2)
      ++skyPixels;
  }
  // For looking at: ENGINE_TERRAIN_PNG=out.png writes the frame.
  if (const char* out = std::getenv("ENGINE_TERRAIN_PNG")) {
    Image image(w, h);
    image.pixels = pixels;
    flipVertically(image);
    EXPECT_TRUE(writePng(out, image).ok());
  }
  const double skyShare = double(skyPixels) / (w * h);
  EXPECT_LT(skyShare, 0.6) << "the terrain should fill most of a view looking down";
  EXPECT_GT(colours.size(), 50u) << "a lit, textured landscape is not a handful of colours";

  // A second frame reuses the resident pages.
  const TerrainDrawStats again = renderer->draw(selection, eye, nullptr);
  EXPECT_EQ(again.pagesUploaded, 0u);
  // The shadow pass's depth-only variant draws the same patches.
  const TerrainDrawStats depthOnly = renderer->drawDepth(selection, camera.viewProjection);
  EXPECT_EQ(depthOnly.patchesDrawn, stats.patchesDrawn);
  EXPECT_EQ(depthOnly.pagesUploaded, 0u);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// 16 km at 1 m spacing. A 320x180 view at 0.125 px selects exactly what 1280x720
// at 0.5 px does (ranges go with viewport height / target): over 4,000 pages and
// 17,000 patches, where the old fixed pool (2,048 slots, 8,192 patches a draw)
// left patches out.
TEST_P(TerrainGl, SixteenKilometresAtHalfAPixelFitTheGpuBudget) {
  // About 20 s on llvmpipe (18 M vertices a draw); the renderer's code path is the
  // same on both backends, which the test above already covers.
  if (GetParam() != Backend::Egl) GTEST_SKIP() << "heavy; run through EGL only";
  const int w = 320, h = 180;
  const double target = 0.125;
  Target frameTarget = makeTarget(w, h);
  TerrainSettings settings = engine::terrain::test::noiseSettings(16384.0, 1500.0, {2.0e6, 0.0, -5.0e6});
  auto terrain = Terrain::create(settings);
  ASSERT_TRUE(terrain.ok()) << terrain.error().message;
  auto renderer = TerrainRenderer::create(engine::test::shaderDir(), *terrain);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  EXPECT_LE(std::size_t(renderer->pageSlots()) * kGpuPageBytes, kDefaultGpuPageBudgetBytes);

  const glm::dvec3 o = settings.origin;
  auto cameraAt = [&](double u, double v) {
    const glm::dvec3 eye(o.x + u, terrain->heightAt(o.x + u, o.z + v) + 40.0, o.z + v);
    return engine::terrain::test::makeCamera(eye, eye + glm::dvec3(1.0, -0.12, 0.7), w, h);
  };
  const LodCamera camera = cameraAt(4000.0, 5000.0);
  const LodSelection selection = selectLodWithin(*terrain, camera, target, std::size_t(renderer->pageSlots()));
  EXPECT_GT(selection.stats.pages, 2048u) << "the view should be demanding";
  EXPECT_GT(selection.patches.size(), 8192u);
  EXPECT_EQ(selection.stats.coarsenings, 0) << "the default budget holds this view at full accuracy";
  const gl::Buffer frame = bindFrame(camera.viewProjection);
  const TerrainDrawStats stats = renderer->draw(selection, camera.position, nullptr);
  EXPECT_EQ(stats.patchesSkipped, 0u);
  EXPECT_EQ(stats.patchesDrawn, selection.patches.size());
  EXPECT_EQ(stats.pagesUploaded, selection.stats.pages) << "a fresh pool uploads each page once";
  EXPECT_EQ(renderer->pagesResident(), int(selection.stats.pages));

  // The smallest pool: the selection is coarsened (and says so) instead of
  // losing patches; a second view far away evicts, and the pool never holds
  // more than its slots.
  auto small = TerrainRenderer::create(engine::test::shaderDir(), *terrain, {}, 0);
  ASSERT_TRUE(small.ok()) << small.error().message;
  EXPECT_EQ(small->pageSlots(), kMinGpuPageSlots);
  std::size_t uploads = 0;
  for (const LodCamera& view : {camera, cameraAt(12000.0, 9000.0)}) {
    const LodSelection coarse = selectLodWithin(*terrain, view, target, std::size_t(small->pageSlots()));
    EXPECT_GT(coarse.stats.coarsenings, 0);
    EXPECT_GT(coarse.stats.targetPixels, target);
    EXPECT_LE(coarse.stats.pages, std::size_t(small->pageSlots()));
    const TerrainDrawStats drawn = small->draw(coarse, view.position, nullptr);
    EXPECT_EQ(drawn.patchesSkipped, 0u);
    EXPECT_EQ(drawn.patchesDrawn, coarse.patches.size());
    EXPECT_LE(small->pagesResident(), small->pageSlots());
    uploads += drawn.pagesUploaded;
  }
  EXPECT_GT(uploads, std::size_t(small->pageSlots())) << "the second view had to evict";
  const LodSelection& fine = selection;
  const glm::dvec3 eye = camera.position;
  // A selection made without the budget is drawn in part, and the loss counted.
  const TerrainDrawStats over = small->draw(fine, eye, nullptr);
  EXPECT_GT(over.patchesSkipped, 0u);
  EXPECT_EQ(over.patchesDrawn + over.patchesSkipped, fine.patches.size());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
