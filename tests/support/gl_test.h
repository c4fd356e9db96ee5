#pragma once
// A real offscreen GL context for tests, parameterised over the backends, with GL
// debug output on: any GL error reported during a test fails it.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "gl/debug.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "platform/gl_context.h"
#include "no_undeclared_uniforms.h"

namespace engine::test {

class GlTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    ContextOptions options;
    options.width = 64;
    options.height = 64;
    options.debug = true;
    auto context = createContext(GetParam(), options);
    ASSERT_TRUE(context.ok()) << context.error().message;
    context_ = std::move(context).value();
    gl::enableDebugOutput();
    gl::resetErrorCount();
  }
  void TearDown() override {
    if (context_) {
      EXPECT_EQ(gl::errorCount(), 0) << "GL reported errors during the test";
    }
  }

  std::unique_ptr<GlContext> context_;
};

inline std::string backendParamName(const ::testing::TestParamInfo<Backend>& info) {
  return std::string(backendName(info.param));
}

#define ENGINE_INSTANTIATE_OFFSCREEN(Suite)                                          \
  INSTANTIATE_TEST_SUITE_P(Offscreen, Suite,                                         \
                           ::testing::Values(::engine::Backend::Egl, ::engine::Backend::OsMesa), \
                           ::engine::test::backendParamName)

// EGL alone, for a suite that compares two things drawn in one context (the GPU
// tracers against the CPU's images, a program set against another, one output path
// against another): which backend made the context does not enter the comparison,
// and the backends' agreement is tested where it is the question
// (cli.egl_osmesa_identical, every golden scene's osmesa instance). The OSMesa
// instances of the six such suites took a third of the plain pass's test time.
#define ENGINE_INSTANTIATE_OFFSCREEN_EGL(Suite)                                      \
  INSTANTIATE_TEST_SUITE_P(Offscreen, Suite, ::testing::Values(::engine::Backend::Egl), \
                           ::engine::test::backendParamName)

inline std::string shaderDir() { return std::string(ENGINE_SOURCE_DIR) + "/shaders"; }

// Runs a test compute shader that reads one Case per invocation from binding 0 and
// writes one Result to binding 1 (local size 64, the count in u_count), as
// test/brdf_eval.comp and test/sampling_eval.comp do: the GPU's compile of a text
// that C++ compiles too, for the test to compare. Empty, with the failure recorded,
// when the shader does not build.
template <typename Result, typename Case>
std::vector<Result> runCases(const std::string& shader, const std::vector<Case>& cases) {
  auto program = gl::Program::build(shaderDir(), {{GL_COMPUTE_SHADER, shader}});
  if (!program) {
    ADD_FAILURE() << program.error().message;
    return {};
  }
  gl::Buffer in = gl::Buffer::create(cases.size() * sizeof(Case), cases.data());
  gl::Buffer out = gl::Buffer::create(cases.size() * sizeof(Result));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
  program->use();
  glUniform1ui(program->location("u_count"), GLuint(cases.size()));
  glDispatchCompute(GLuint((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<Result> results(cases.size());
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(results.size() * sizeof(Result)), results.data());
  return results;
}

}  // namespace engine::test
