// A scene with no HDR effect skips the HDR target and the post pass: its fragment
// shaders apply the exposure, the tone map and the curve (common/output.glsl) and
// write display values into an RGBA8 target. The post pass rounded the radiance to
// half floats before the same curve, so the two paths may differ by one level, and by
// no more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <set>
#include <vector>

#include "../support/gl_test.h"
#include "asset/scene_file.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// Classic and PBR shading, a texture-less robot, shapes, a sun's shadow and a
// point light; no sky, tone map or MSAA: what directOutput asks.
constexpr const char* kDirectOutputScene = R"({
  "camera": {"position": [0, 2.2, 5], "target": [0, 0.8, 0], "fovy": 50},
  "lights": [{"type": "sun", "direction": [-0.4, 1, 0.3], "intensity": 1.5, "shadows": true},
             {"type": "point", "position": [1.5, 2, 1.5], "intensity": 3}],
  "materials": {"ground": {"color": [0.6, 0.6, 0.55]}, "red": {"color": [0.9, 0.1, 0.1]}},
  "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "ground"},
                 {"type": "sphere", "center": [1.2, 0.5, 0], "radius": 0.5, "material": "red"}],
  "models": [{"path": "../models/character.gltf", "position": [-0.5, 0, 0], "clip": "Walk"}],
  "sky": {"enabled": false, "background": [0.3, 0.5, 0.8]},
  "render": {"tonemap": "none", "shading": "%s", "output": "%s"}
})";

struct DirectFrame {
  Image image;
  std::string described;
};

DirectFrame renderDirectOrPost(const SceneDesc& scene, bool hdrTarget) {
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  options.hdrTarget = hdrTarget;
  auto renderer = SceneRenderer::create(scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  EXPECT_TRUE((*renderer)->update(0.4).ok());
  auto target = RenderTarget::create(192, 128, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  const Status status = (*renderer)->render((*renderer)->initialCamera(), 192, 128);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return {target->readPixels(), (*renderer)->describe()};
}

// The direct frame against the post pass's: a level at most, and few of them.
void expectWithinOneLevelOfThePostPass(const SceneDesc& scene, const std::string& what) {
  const DirectFrame direct = renderDirectOrPost(scene, false), post = renderDirectOrPost(scene, true);
  EXPECT_NE(direct.described.find("direct("), std::string::npos) << direct.described;
  EXPECT_NE(post.described.find("post("), std::string::npos) << post.described;
  ASSERT_EQ(direct.image.pixels.size(), post.image.pixels.size());
  int largest = 0;
  size_t differing = 0;
  for (size_t i = 0; i < direct.image.pixels.size(); ++i) {
    const int d = std::abs(int(direct.image.pixels[i]) - int(post.image.pixels[i]));
    largest = std::max(largest, d);
    differing += d != 0;
  }
  EXPECT_LE(largest, 1);
  // Only values near a level's boundary move with the half-float rounding:
  // measured 0.4 % (sRGB) and 5.6-6.3 % (gamma 2.2) of the channels (RGBA;
  // alpha never). A broken curve (linear values, the curve or the tone map applied
  // twice or not at all) moves nearly all of them, and by far more than one level.
  std::printf("%s: %zu of %zu channels differ by one level\n", what.c_str(), differing, direct.image.pixels.size());
  EXPECT_LT(differing, direct.image.pixels.size() / 8);
}

std::string directOutputScene(const char* shading, const char* output) {
  char text[4096];
  std::snprintf(text, sizeof(text), kDirectOutputScene, shading, output);
  return text;
}

}  // namespace

class DirectOutput : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(DirectOutput);

TEST_P(DirectOutput, DiffersFromThePostPassByAtMostOneLevel) {
  for (const char* shading : {"classic", "pbr"}) {
    for (const char* output : {"srgb", "gamma2.2"}) {
      SCOPED_TRACE(std::string(shading) + ", " + output);
      auto scene = parseScene(directOutputScene(shading, output), std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/direct.json");
      ASSERT_TRUE(scene.ok()) << scene.error().message;
      expectWithinOneLevelOfThePostPass(*scene, std::string(shading) + ", " + output);
    }
  }
}

// Exposure and the tone maps are per pixel too, and the sky writes display values
// like the surfaces: scenes with them go direct, within a level of the post pass.
TEST_P(DirectOutput, ToneMapsExposureAndTheSkyGoDirectWithinOneLevel) {
  const std::string base = directOutputScene("pbr", "srgb");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"tonemap\": \"none\"", "\"tonemap\": \"aces\""},
        {"\"tonemap\": \"none\"", "\"tonemap\": \"reinhard\", \"exposure\": 2.5"},
        {"\"tonemap\": \"none\"", "\"tonemap\": \"aces\", \"exposure\": 0.7"},
        {"\"enabled\": false", "\"enabled\": true"}}) {
    SCOPED_TRACE(to);
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    auto scene = parseScene(text, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/direct.json");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    expectWithinOneLevelOfThePostPass(*scene, to);
  }
}

// What needs the linear image keeps the HDR target: MSAA's resolve and supersampling's
// average come before the tone map.
TEST_P(DirectOutput, ScenesThatNeedTheHdrTargetKeepIt) {
  const std::string base = directOutputScene("pbr", "srgb");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"tonemap\": \"none\"", "\"tonemap\": \"aces\", \"msaa\": 4"},
        {"\"tonemap\": \"none\"", "\"tonemap\": \"none\", \"supersample\": 2"}}) {
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    auto scene = parseScene(text, std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/direct.json");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_NE(renderDirectOrPost(*scene, false).described.find("post("), std::string::npos) << to;
  }
}

namespace {

// The bytes of the bound read framebuffer's colour, bottom row first.
std::vector<unsigned char> readColour(GLuint framebuffer, int width, int height) {
  std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return pixels;
}

struct CallerFramebuffer {
  gl::Texture color;
  gl::Renderbuffer depth;
  gl::Framebuffer framebuffer;
};

CallerFramebuffer callerFramebuffer(GLenum depthFormat, int width, int height) {
  CallerFramebuffer c{gl::Texture::create2D(GL_RGBA8, width, height, 1),
                      gl::Renderbuffer::create(depthFormat, width, height), gl::Framebuffer::create()};
  c.framebuffer.attach(GL_COLOR_ATTACHMENT0, c.color);
  c.framebuffer.attach(GL_DEPTH_ATTACHMENT, c.depth);
  return c;
}

}  // namespace

// The direct path draws straight into a caller's framebuffer that can hold its frame
// (RenderTarget's SRGB8_ALPHA8, or RGBA8, with float depth), and into a target of its
// own copied out where it cannot (fixed-point depth): the same bytes either way, from
// one renderer switching between the two.
TEST_P(DirectOutput, DrawsIntoTheCallersFramebufferOrCopiesTheSameBytes) {
  auto scene = parseScene(directOutputScene("pbr", "srgb"), std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/direct.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  auto renderer = SceneRenderer::create(*scene, options);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  ASSERT_TRUE((*renderer)->update(0.4).ok());
  constexpr int kW = 192, kH = 128;
  auto render = [&](GLuint framebuffer) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    const Status status = (*renderer)->render((*renderer)->initialCamera(), kW, kH);
    EXPECT_TRUE(status.ok()) << status.error().message;
    return (*renderer)->stats().frameCopies;
  };
  auto target = RenderTarget::create(kW, kH, 1);
  ASSERT_TRUE(target.ok());
  const CallerFramebuffer fixedDepth = callerFramebuffer(GL_DEPTH_COMPONENT24, kW, kH);
  const CallerFramebuffer floatDepth = callerFramebuffer(GL_DEPTH_COMPONENT32F, kW, kH);
  ASSERT_TRUE(fixedDepth.framebuffer.complete() && floatDepth.framebuffer.complete());

  target->bind();  // as the runners bind it: GL_FRAMEBUFFER_SRGB on
  GLint targetFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &targetFramebuffer);
  EXPECT_EQ(render(GLuint(targetFramebuffer)), 0);
  EXPECT_EQ(render(fixedDepth.framebuffer.id()), 1);
  EXPECT_EQ(render(floatDepth.framebuffer.id()), 0);
  GLint drawn = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
  EXPECT_EQ(GLuint(drawn), floatDepth.framebuffer.id()) << "the caller's framebuffer is bound again";

  Image fromTarget = target->readPixels();
  flipVertically(fromTarget);  // back to GL's bottom row first
  const std::vector<unsigned char> copied = readColour(fixedDepth.framebuffer.id(), kW, kH);
  EXPECT_TRUE(fromTarget.pixels == copied) << "RenderTarget against the copy";
  EXPECT_TRUE(readColour(floatDepth.framebuffer.id(), kW, kH) == copied) << "RGBA8 caller against the copy";
}

// With the deferred terrain the direct path draws into its own framebuffer with the
// caller's colour image attached (no copy): demo.json (a terrain, no HDR effect).
// A caller that replaces its target between frames (a resized window's) has a new
// image; the frame must land in it, the same bytes as in the first. (Mesa names the
// new image anew; the renderer attaches the caller's image every frame, so a
// driver that reused the deleted one's name would be served too.)
TEST_P(DirectOutput, TheDeferredTerrainDrawsIntoTheCallersNewTarget) {
  auto scene = loadSceneFile(std::string(ENGINE_SOURCE_DIR) + "/assets/scenes/demo.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  SceneRenderOptions options;
  options.shaderDir = test::shaderDir();
  auto renderer = SceneRenderer::create(*scene, options);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  ASSERT_TRUE((*renderer)->update(1.0).ok());
  constexpr int kW = 192, kH = 108;
  auto frameIn = [&](const RenderTarget& target) {
    target.bind();
    const Status status = (*renderer)->render((*renderer)->initialCamera(), kW, kH);
    EXPECT_TRUE(status.ok()) << status.error().message;
    EXPECT_EQ((*renderer)->stats().frameCopies, 0) << "the caller's image is drawn into, not copied to";
    return target.readPixels();
  };
  Image first;
  {
    auto target = RenderTarget::create(kW, kH, 1);
    ASSERT_TRUE(target.ok());
    first = frameIn(*target);
  }
  auto replaced = RenderTarget::create(kW, kH, 1);
  ASSERT_TRUE(replaced.ok());
  const Image second = frameIn(*replaced);
  EXPECT_NE((*renderer)->describe().find("deferred"), std::string::npos);
  EXPECT_TRUE(first.pixels == second.pixels) << "the replaced target's frame";
  // Not a blank frame: the sky's and the ground's colours both show.
  std::set<std::uint32_t> colours;
  for (size_t i = 0; i + 3 < second.pixels.size(); i += 4)
    colours.insert(std::uint32_t(second.pixels[i]) << 16 | std::uint32_t(second.pixels[i + 1]) << 8 | second.pixels[i + 2]);
  EXPECT_GT(colours.size(), 100u);
}
