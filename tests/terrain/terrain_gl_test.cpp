// The terrain renderer against a real offscreen context: it builds, draws a
// selection without GL errors and gives a plausible picture (ground, not sky
// everywhere, and not one flat colour).
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "core/image.h"

#include "../support/gl_test.h"
#include "gl/resources.h"
#include "terrain/lod.h"
#include "terrain/terrain_renderer.h"
#include "terrain_support.h"

using namespace engine;
using namespace engine::terrain;
using engine::test::GlTest;

class TerrainGl : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(TerrainGl);

namespace {

void setLighting(const gl::Program& p) {
  p.set("u_sunDirection", glm::normalize(glm::vec3(0.5f, 0.8f, 0.3f)));
  p.set("u_sunColor", glm::vec3(1.3f, 1.22f, 1.1f));
  p.set("u_skyColor", glm::vec3(0.22f, 0.28f, 0.38f));
  p.set("u_groundColor", glm::vec3(0.1f, 0.09f, 0.07f));
  p.set("u_fogColor", glm::vec3(0.6f, 0.7f, 0.85f));
  p.set("u_fogDensity", 0.0002f);
}

}  // namespace

TEST_P(TerrainGl, DrawsAPlausibleLandscapeFarFromTheOrigin) {
  const int w = 160, h = 90;
  gl::Texture color = gl::Texture::create2D(GL_SRGB8_ALPHA8, w, h);
  gl::Renderbuffer depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h);
  gl::Framebuffer fb = gl::Framebuffer::create();
  fb.attach(GL_COLOR_ATTACHMENT0, color);
  fb.attach(GL_DEPTH_ATTACHMENT, depth);
  ASSERT_TRUE(fb.complete());

  TerrainSettings settings = engine::terrain::test::noiseSettings(4096.0, 600.0, {5.0e6, 100.0, -7.0e6});
  auto terrain = Terrain::create(settings);
  ASSERT_TRUE(terrain.ok()) << terrain.error().message;
  auto renderer = TerrainRenderer::create(engine::test::shaderDir(), *terrain);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;

  const glm::dvec3 o = settings.origin;
  const glm::dvec3 eye(o.x + 1000.0, terrain->heightAt(o.x + 1000.0, o.z + 1000.0) + 150.0, o.z + 1000.0);
  const LodCamera camera = engine::terrain::test::makeCamera(eye, eye + glm::dvec3(1.0, -0.25, 1.0), w, h);
  const LodSelection selection = selectLod(*terrain, camera, 2.0);

  fb.bind();
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glEnable(GL_FRAMEBUFFER_SRGB);
  const float sky[4] = {0.6f, 0.7f, 0.85f, 1.0f};
  glClearBufferfv(GL_COLOR, 0, sky);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
  const TerrainDrawStats stats = renderer->draw(selection, camera.viewProjection, eye, setLighting);
  EXPECT_EQ(stats.patchesSkipped, 0u);
  EXPECT_GT(stats.patchesDrawn, 0u);
  EXPECT_EQ(stats.trianglesDrawn, selection.stats.triangles);

  std::vector<std::uint8_t> pixels(std::size_t(w) * h * 4);
  glGetTextureImage(color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
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
  const TerrainDrawStats again = renderer->draw(selection, camera.viewProjection, eye, setLighting);
  EXPECT_EQ(again.pagesUploaded, 0u);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
