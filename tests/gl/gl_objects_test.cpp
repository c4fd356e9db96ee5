// GL layer against a real offscreen context, through EGL and OSMesa.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <type_traits>

#include "../support/gl_test.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "app/runner.h"
#include "render/model_renderer.h"
#include "render/render_target.h"

using namespace engine;
using engine::test::GlTest;

// Magnum's habit: GL owners are move-only.
static_assert(!std::is_copy_constructible_v<gl::Buffer>);
static_assert(!std::is_copy_assignable_v<gl::Texture>);
static_assert(std::is_nothrow_move_constructible_v<gl::Framebuffer>);
static_assert(!std::is_copy_constructible_v<gl::Program>);
static_assert(!std::is_copy_assignable_v<gl::Sampler>);
static_assert(std::is_nothrow_move_constructible_v<gl::Sampler>);

class GlObjects : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GlObjects);

TEST_P(GlObjects, ContextIsOpenGl45Core) {
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_FALSE(context_->renderer().empty());
}

TEST_P(GlObjects, BufferHoldsItsDataAndMovesOwnership) {
  const float data[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  gl::Buffer a = gl::Buffer::create(sizeof data, data);
  const GLuint id = a.id();
  ASSERT_NE(id, 0u);
  gl::Buffer b = std::move(a);
  EXPECT_EQ(a.id(), 0u);
  EXPECT_EQ(b.id(), id);
  float back[4] = {};
  glGetNamedBufferSubData(b.id(), 0, sizeof back, back);
  EXPECT_EQ(back[2], 3.0f);
  b.reset();
  EXPECT_FALSE(glIsBuffer(id));
}

TEST_P(GlObjects, DestructorDeletesTheName) {
  GLuint id = 0;
  {
    gl::Texture t = gl::Texture::create2D(GL_RGBA8, 4, 4);
    id = t.id();
    EXPECT_TRUE(glIsTexture(id));
  }
  EXPECT_FALSE(glIsTexture(id));
}

TEST_P(GlObjects, RenderTargetReadsBackTheClearColour) {
  auto target = RenderTarget::create(8, 4, 1);
  ASSERT_TRUE(target.ok()) << target.error().message;
  target->bind();
  // sRGB target: linear 0.5 is stored as 188 (the sRGB curve), 1.0 as 255.
  glClearColor(1.0f, 0.5f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const Image image = target->readPixels();
  EXPECT_EQ(image.width, 8);
  EXPECT_EQ(image.at(3, 2)[0], 255);
  EXPECT_NEAR(image.at(3, 2)[1], 188, 1);
  EXPECT_EQ(image.at(3, 2)[2], 0);
}

TEST_P(GlObjects, MultisampledTargetResolves) {
  auto target = RenderTarget::create(8, 8, 4);
  ASSERT_TRUE(target.ok()) << target.error().message;
  target->bind();
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  target->resolve();
  EXPECT_EQ(target->readPixels().at(7, 7)[2], 255);
}

TEST_P(GlObjects, ImpossibleSampleCountIsAnError) {
  auto target = RenderTarget::create(8, 8, 1024);
  ASSERT_FALSE(target.ok());
  EXPECT_NE(target.error().message.find("1024"), std::string::npos);
}

TEST_P(GlObjects, DebugOutputCountsErrors) {
  glBindBuffer(GL_ARRAY_BUFFER, 123456);  // not a buffer name: GL_INVALID_OPERATION
  EXPECT_GT(gl::errorCount(), 0);
  gl::resetErrorCount();
}

TEST_P(GlObjects, ProjectShadersCompile) {
  for (const auto& pair : std::vector<std::pair<std::string, std::string>>{
           {"scene.vert", "scene.frag"}, {"sky.vert", "sky.frag"}}) {
    auto program = gl::Program::build(test::shaderDir(), {{GL_VERTEX_SHADER, pair.first},
                                                          {GL_FRAGMENT_SHADER, pair.second}});
    EXPECT_TRUE(program.ok()) << program.error().message;
  }
}

class ShaderErrors : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    dir_ = std::filesystem::temp_directory_path() /
           ("engine_gl_shaders_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::filesystem::remove_all(dir_);
    GlTest::TearDown();
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  std::filesystem::path dir_;
};
ENGINE_INSTANTIATE_OFFSCREEN(ShaderErrors);

// A uniform the linked program does not use is ignored, as GL ignores it; one that no
// stage declares (a typo, a stale name) is reported, once.
TEST_P(ShaderErrors, SettingAnUndeclaredUniformIsReported) {
  write("u.comp",
        "#version 450\nlayout(local_size_x = 1) in;\nuniform float u_unused;\n"
        "#ifdef NEVER\nuniform float u_hidden;\n#endif\nvoid main() {}\n");
  auto program = gl::Program::build(dir_.string(), {{GL_COMPUTE_SHADER, "u.comp"}});
  ASSERT_TRUE(program.ok()) << program.error().message;
  gl::forgetUndeclaredUniforms();
  program->set("u_unused", 1.0f);
  program->set("u_hidden", 1.0f);
  EXPECT_TRUE(gl::undeclaredUniformsSet().empty());
  program->set("u_typo", 1.0f);
  program->set("u_typo", 2.0f);
  program->set("u_typo[1].x", 2.0f);
  EXPECT_EQ(gl::undeclaredUniformsSet(), (std::vector<std::string>{"u.comp: u_typo", "u.comp: u_typo[1].x"}));
  gl::forgetUndeclaredUniforms();
}

TEST_P(ShaderErrors, CompileErrorNamesTheIncludedFileAndLine) {
  write("helper.glsl", "float helper() {\n  return undefinedThing;\n}\n");
  write("main.frag",
        "#version 450 core\n#include \"helper.glsl\"\nout vec4 c;\nvoid main() { c = vec4(helper()); }\n");
  write("main.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n");
  auto program = gl::Program::build(dir_.string(), {{GL_VERTEX_SHADER, "main.vert"},
                                                    {GL_FRAGMENT_SHADER, "main.frag"}});
  ASSERT_FALSE(program.ok());
  EXPECT_NE(program.error().message.find("helper.glsl:2"), std::string::npos)
      << program.error().message;
}

TEST_P(ShaderErrors, LinkErrorNamesTheStages) {
  write("a.vert", "#version 450 core\nout vec3 v_x;\nvoid main() { v_x = vec3(1.0); gl_Position = vec4(0.0); }\n");
  write("a.frag", "#version 450 core\nin vec4 v_x;\nout vec4 c;\nvoid main() { c = v_x; }\n");
  auto program = gl::Program::build(dir_.string(), {{GL_VERTEX_SHADER, "a.vert"},
                                                    {GL_FRAGMENT_SHADER, "a.frag"}});
  ASSERT_FALSE(program.ok());
  EXPECT_NE(program.error().message.find("a.vert + a.frag: link failed"), std::string::npos)
      << program.error().message;
}

// A capture program (transform feedback) of a variant must not replace the cached
// plain program of that variant: a pointer handed out before stays the program it
// was, and the cache hands out that same one after (ASan sees a use after free if
// the capture's build deletes it).
TEST_P(GlObjects, CaptureProgramsKeepTheCachedVariant) {
  ShaderVariants variants(test::shaderDir());
  const ShaderVariant variant{4, SkinMode::Linear};
  auto plain = variants.get(variant);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  const gl::Program* cached = *plain;
  const GLuint id = cached->id();
  auto capture = variants.get(variant, {"v_position"});
  ASSERT_TRUE(capture.ok()) << capture.error().message;
  EXPECT_NE(*capture, cached);
  EXPECT_NE((*capture)->id(), id);
  EXPECT_EQ(cached->id(), id);
  EXPECT_TRUE(glIsProgram(id));
  GLint varyings = -1;
  glGetProgramiv(id, GL_TRANSFORM_FEEDBACK_VARYINGS, &varyings);
  EXPECT_EQ(varyings, 0) << "the cached plain program was replaced by the capture";
  auto again = variants.get(variant);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, cached);
  auto captureAgain = variants.get(variant, {"v_position"});
  ASSERT_TRUE(captureAgain.ok());
  EXPECT_EQ(*captureAgain, *capture);
  EXPECT_EQ(variants.built().size(), 1u);  // --describe lists what frames draw with
}

// Every framebuffer the renderers make is checked by name: an incomplete one is
// an error naming it and the GL status, not a frame drawn into nothing.
TEST_P(GlObjects, IncompleteFramebufferIsNamed) {
  gl::Framebuffer empty = gl::Framebuffer::create();
  auto status = empty.check("shadow-sun");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().message,
            "framebuffer \"shadow-sun\" is incomplete: GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT (0x8CD7)");
  // Attachments of different sizes are complete in GL 4.5 (the common area is
  // drawn); a colour texture with a depth renderbuffer is the usual pair.
  gl::Texture color = gl::Texture::create2D(GL_RGBA8, 8, 8, 1);
  gl::Framebuffer fbo = gl::Framebuffer::create();
  fbo.attach(GL_COLOR_ATTACHMENT0, color);
  EXPECT_TRUE(fbo.check("probe").ok());
  // A multisampled depth with a single-sampled colour: incomplete multisample.
  gl::Renderbuffer depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, 8, 8, 4);
  fbo.attach(GL_DEPTH_ATTACHMENT, depth);
  auto mixed = fbo.check("probe");
  ASSERT_FALSE(mixed.ok());
  EXPECT_NE(mixed.error().message.find("\"probe\""), std::string::npos);
  EXPECT_NE(mixed.error().message.find("INCOMPLETE_MULTISAMPLE"), std::string::npos) << mixed.error().message;
}

namespace {

// A game that owns a GL object and fails where it is told to: in init (after
// making its object), in the first frame, or not at all.
class FailingGame final : public Game {
 public:
  enum class FailAt { Nothing, Init, Render };
  explicit FailingGame(FailAt at) : at_(at) {}
  Status init() override {
    buffer_ = gl::Buffer::create(64);
    if (at_ == FailAt::Init) return makeError("init failed half-way");
    return Ok{};
  }
  void update(double, double) override {}
  Status render(const FrameInfo&) override {
    if (at_ == FailAt::Render) return makeError("the frame failed");
    return Ok{};
  }
  Camera& camera() override { return camera_; }
  void shutdown() override {
    ++shutdowns;
    buffer_.reset();
  }
  int shutdowns = 0;

 private:
  FailAt at_;
  Camera camera_;
  gl::Buffer buffer_;
};

}  // namespace

// However a run ends, the game is shut down once, before its context goes: none of
// its GL objects outlives the context (gl::orphanedObjects counts those that do).
TEST(RunLifetime, EveryEndShutsTheGameDownBeforeTheContext) {
  for (Backend backend : {Backend::Egl, Backend::OsMesa}) {
    for (auto at : {FailingGame::FailAt::Nothing, FailingGame::FailAt::Init, FailingGame::FailAt::Render}) {
      FailingGame game(at);
      RunOptions options;
      options.width = options.height = 16;
      options.frames = 2;
      const long long orphansBefore = gl::orphanedObjects(), liveBefore = gl::liveObjects();
      const Status status = runHeadless(backend, game, options);
      EXPECT_EQ(status.ok(), at == FailingGame::FailAt::Nothing);
      EXPECT_EQ(game.shutdowns, 1);
      EXPECT_EQ(gl::orphanedObjects(), orphansBefore);
      EXPECT_EQ(gl::liveObjects(), liveBefore);
    }
  }
  // msaa 64 is beyond every GL: the target fails after a successful init.
  FailingGame game(FailingGame::FailAt::Nothing);
  RunOptions options;
  options.msaa = 64;
  const long long orphansBefore = gl::orphanedObjects();
  EXPECT_FALSE(runHeadless(Backend::Egl, game, options).ok());
  EXPECT_EQ(game.shutdowns, 1);
  EXPECT_EQ(gl::orphanedObjects(), orphansBefore);
}
