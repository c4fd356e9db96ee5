#pragma once
// A real offscreen GL context for tests, parameterised over the backends, with GL
// debug output on: any GL error reported during a test fails it.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "gl/debug.h"
#include "platform/gl_context.h"

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

inline std::string shaderDir() { return std::string(ENGINE_SOURCE_DIR) + "/shaders"; }

}  // namespace engine::test
