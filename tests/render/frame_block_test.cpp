// The frame block is one text (shaders/common/frame.glsl): GLSL's uniform block and
// C++'s struct (render/frame_block.h). The GPU's compiler lays it out by std140; the
// C++ compiler by its own rules: every member's offset, the arrays' and matrices'
// strides and the block's size must agree, or the renderer's upload would feed the
// shaders shifted values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "../support/gl_test.h"
#include "render/frame_block.h"

namespace engine {
namespace {

using test::GlTest;
using frametext::Frame;

class FrameBlockText : public GlTest {};

// Each member's C++ offset, by the name GL gives it (an array's first element).
const std::map<std::string, std::size_t>& cppOffsets() {
  static const std::map<std::string, std::size_t> offsets = {
      {"u_viewProjection", offsetof(Frame, u_viewProjection)},
      {"u_sunShadowMatrix", offsetof(Frame, u_sunShadowMatrix)},
      {"u_sunDirection", offsetof(Frame, u_sunDirection)},
      {"u_sunColor", offsetof(Frame, u_sunColor)},
      {"u_pointPosition[0]", offsetof(Frame, u_pointPosition)},
      {"u_pointColor[0]", offsetof(Frame, u_pointColor)},
      {"u_pointAxis[0]", offsetof(Frame, u_pointAxis)},
      {"u_pointInner[0]", offsetof(Frame, u_pointInner)},
      {"u_ambientSky", offsetof(Frame, u_ambientSky)},
      {"u_ambientGround", offsetof(Frame, u_ambientGround)},
      {"u_fog", offsetof(Frame, u_fog)},
      {"u_shadowParams", offsetof(Frame, u_shadowParams)},
      {"u_counts", offsetof(Frame, u_counts)},
      {"u_sunShadowMatrixFar", offsetof(Frame, u_sunShadowMatrixFar)},
      {"u_sunFarParams", offsetof(Frame, u_sunFarParams)},
      {"u_shIrradiance[0]", offsetof(Frame, u_shIrradiance)},
      {"u_iblParams", offsetof(Frame, u_iblParams)},
  };
  return offsets;
}

TEST_P(FrameBlockText, TheGlsLayoutIsTheCppStructs) {
  auto program = gl::Program::build(test::shaderDir(), {{GL_COMPUTE_SHADER, "test/frame_block.comp"}});
  ASSERT_TRUE(program.ok()) << program.error().message;
  const GLuint id = program->id();
  const GLuint block = glGetProgramResourceIndex(id, GL_UNIFORM_BLOCK, "Frame");
  ASSERT_NE(block, GL_INVALID_INDEX);
  const GLenum sizeProp = GL_BUFFER_DATA_SIZE;
  GLint size = 0;
  glGetProgramResourceiv(id, GL_UNIFORM_BLOCK, block, 1, &sizeProp, 1, nullptr, &size);
  EXPECT_EQ(std::size_t(size), sizeof(FrameBlock));
  const GLenum countProp = GL_NUM_ACTIVE_VARIABLES;
  GLint count = 0;
  glGetProgramResourceiv(id, GL_UNIFORM_BLOCK, block, 1, &countProp, 1, nullptr, &count);
  // std140: every member is active, so a member C++ has no entry for is counted.
  EXPECT_EQ(std::size_t(count), cppOffsets().size());
  std::vector<GLint> members(size_t(std::max(count, 0)));
  const GLenum membersProp = GL_ACTIVE_VARIABLES;
  glGetProgramResourceiv(id, GL_UNIFORM_BLOCK, block, 1, &membersProp, count, nullptr, members.data());
  for (const GLint member : members) {
    char name[64] = {};
    glGetProgramResourceName(id, GL_UNIFORM, GLuint(member), sizeof(name), nullptr, name);
    const GLenum props[] = {GL_OFFSET, GL_ARRAY_STRIDE, GL_MATRIX_STRIDE, GL_TYPE};
    GLint values[4] = {};
    glGetProgramResourceiv(id, GL_UNIFORM, GLuint(member), 4, props, 4, nullptr, values);
    const auto it = cppOffsets().find(name);
    ASSERT_NE(it, cppOffsets().end()) << name << ": a member the test does not know";
    EXPECT_EQ(std::size_t(values[0]), it->second) << name;
    // Arrays of vec4, and mat4's columns: 16 bytes apart, as glm's are.
    if (values[1] > 0) {
      EXPECT_EQ(values[1], 16) << name;
    }
    if (values[3] == GL_FLOAT_MAT4) {
      EXPECT_EQ(values[2], 16) << name;
    }
  }
}

ENGINE_INSTANTIATE_OFFSCREEN(FrameBlockText);

}  // namespace
}  // namespace engine
