// The display curves as a frame stores them: common/output.glsl's table lookups,
// drawn into an 8-bit target and read back, give core/srgb_curve.h's exact bytes for
// values on both sides of every byte step (within 64 float ulps, where an
// approximate curve or a wrong threshold gives the other byte) and for random
// values: the post pass's sRGB curve, and a direct-output fragment's ACES and sRGB.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
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

constexpr int kProbeWidth = 512, kProbeHeight = 256;

// 129 floats around each of the table's 255 step thresholds, then random values
// of its domain, to fill a frame.
std::vector<float> probeValues(const DisplayTable& table) {
  std::vector<float> values;
  for (int bin = 0; bin < table.bins(); ++bin) {
    const float threshold = table.texels[size_t(2 * bin + 1)];
    if (std::isinf(threshold)) continue;
    const std::uint32_t at = std::bit_cast<std::uint32_t>(threshold);
    for (std::uint32_t bits = at - 64; bits <= at + 64; ++bits) values.push_back(std::bit_cast<float>(bits));
  }
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> uniform(0.0f, table.domain);
  while (values.size() < size_t(kProbeWidth * kProbeHeight)) values.push_back(uniform(rng));
  values.resize(size_t(kProbeWidth * kProbeHeight));
  return values;
}

// How many of the frame's pixels (drawn by test/display_eval.frag with `defines`,
// reading `table`) differ from `byteOf`; the first few are reported.
int wrongPixels(const DisplayTable& table, std::uint8_t (*byteOf)(float), const std::vector<std::string>& defines) {
  const std::vector<float> values = probeValues(table);
  auto program = gl::Program::build(test::shaderDir(),
                                    {{GL_VERTEX_SHADER, "post.vert"}, {GL_FRAGMENT_SHADER, "test/display_eval.frag"}},
                                    defines);
  EXPECT_TRUE(program) << program.error().message;
  auto target = RenderTarget::create(kProbeWidth, kProbeHeight, 1);
  EXPECT_TRUE(target) << target.error().message;
  if (!program || !target) return -1;
  const gl::Buffer texels = gl::Buffer::create(table.texels.size() * sizeof(float), table.texels.data(), 0);
  const gl::Texture lookup = gl::Texture::ofBuffer(texels, GL_RG32F);
  const gl::Buffer input = gl::Buffer::create(values.size() * sizeof(float), values.data(), 0);
  const gl::VertexArray vao = gl::VertexArray::create();
  lookup.bind(gl::binding::kDisplayTable);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
  target->bind();
  // The target is SRGB8_ALPHA8: its own encoding off, it stores the shader's bytes,
  // as the scene renderer has it.
  glDisable(GL_FRAMEBUFFER_SRGB);
  program->use();
  program->set("u_width", kProbeWidth);
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const Image image = target->readPixels();  // top row first
  int wrong = 0;
  for (int y = 0; y < kProbeHeight; ++y) {
    for (int x = 0; x < kProbeWidth; ++x) {
      const float v = values[size_t((kProbeHeight - 1 - y) * kProbeWidth + x)];
      const std::uint8_t* px = image.at(x, y);
      const std::uint8_t exact = byteOf(v);
      if ((px[0] != exact || px[1] != exact || px[2] != exact) && ++wrong <= 5)
        ADD_FAILURE() << "value " << v << ": stored " << int(px[0]) << ", exact " << int(exact);
    }
  }
  return wrong;
}

}  // namespace

class DisplayOutput : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(DisplayOutput);

TEST_P(DisplayOutput, ThePostPassStoresTheExactSrgbCurve) {
  EXPECT_EQ(wrongPixels(srgbTable(), srgbByte, {}), 0);
}

TEST_P(DisplayOutput, DirectFragmentsStoreExactAcesAndSrgb) {
  EXPECT_EQ(wrongPixels(acesSrgbTable(), acesSrgbByte, {"DIRECT_OUTPUT 1", "TONE_MAP 2", "EXPOSURE 1"}), 0);
}
