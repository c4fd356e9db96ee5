// The sRGB curve as a frame stores it: common/output.glsl's table lookup, drawn into
// an 8-bit target and read back, gives core/srgb_curve.h's exact byte for values on
// both sides of every byte step (within 64 float ulps, where an approximate curve
// or a wrong threshold would give the other byte) and for random values.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "../support/gl_test.h"
#include "core/srgb_curve.h"
#include "gl/bindings.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "render/render_target.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// Linear values: 129 floats around each of the table's 255 step thresholds, then
// random ones, to fill a whole frame.
std::vector<float> probeValues(const std::vector<float>& table, size_t count) {
  std::vector<float> values;
  for (int bin = 0; bin < kSrgbTableBins; ++bin) {
    const float threshold = table[size_t(2 * bin + 1)];
    if (threshold > 1.0f) continue;
    const std::uint32_t at = std::bit_cast<std::uint32_t>(threshold);
    for (std::uint32_t bits = at - 64; bits <= at + 64; ++bits) values.push_back(std::bit_cast<float>(bits));
  }
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  while (values.size() < count) values.push_back(uniform(rng));
  values.resize(count);
  return values;
}

}  // namespace

class SrgbOutput : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(SrgbOutput);

TEST_P(SrgbOutput, FramesStoreTheExactCurve) {
  constexpr int kWidth = 512, kHeight = 256;
  const std::vector<float> table = srgbEncodeTable();
  const std::vector<float> values = probeValues(table, size_t(kWidth * kHeight));
  auto program = gl::Program::build(test::shaderDir(),
                                    {{GL_VERTEX_SHADER, "post.vert"}, {GL_FRAGMENT_SHADER, "test/srgb_eval.frag"}});
  ASSERT_TRUE(program) << program.error().message;
  auto target = RenderTarget::create(kWidth, kHeight, 1);
  ASSERT_TRUE(target) << target.error().message;
  const gl::Buffer texels = gl::Buffer::create(table.size() * sizeof(float), table.data(), 0);
  const gl::Texture lookup = gl::Texture::ofBuffer(texels, GL_RG32F);
  const gl::Buffer input = gl::Buffer::create(values.size() * sizeof(float), values.data(), 0);
  const gl::VertexArray vao = gl::VertexArray::create();
  lookup.bind(gl::binding::kSrgbTable);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
  target->bind();
  // The target is SRGB8_ALPHA8: its own encoding off, it stores the shader's bytes,
  // as the direct path has it.
  glDisable(GL_FRAMEBUFFER_SRGB);
  program->use();
  program->set("u_width", kWidth);
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const Image image = target->readPixels();  // top row first
  int wrong = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float v = values[size_t((kHeight - 1 - y) * kWidth + x)];
      const std::uint8_t* px = image.at(x, y);
      if (px[0] != srgbByte(v) || px[1] != srgbByte(v) || px[2] != srgbByte(v)) {
        if (++wrong <= 5) ADD_FAILURE() << "value " << v << ": stored " << int(px[0]) << ", exact " << int(srgbByte(v));
      }
    }
  }
  EXPECT_EQ(wrong, 0);
}
