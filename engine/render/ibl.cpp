#include "render/ibl.h"

#include <algorithm>
#include <bit>
#include <sstream>

#include "gl/bindings.h"
#include "gl/shader.h"

namespace engine {
namespace {

// The BRDF table: 32 x 32 entries of 256 visible-normal samples per lobe. Its
// entries vary smoothly (bilinear filtering between them suffices), and 256 points
// leave an entry within 0.003 of a 65536-point integral (tests/core/ibl_tables_test.cpp's comparison
// with a quadrature). About 45 ms on one core, once per process: it depends on the
// BRDF alone, not on the scene.
constexpr int kSplitSumSize = 32;
constexpr int kSplitSumSamples = 256;
// GGX samples per prefiltered texel: with filtered importance sampling 128 come
// within 1.6 % of the exact convolution (64: 2.3 %, tests/render/ibl_test.cpp); the
// chain's cost grows with them (about 1.5 ms per sample at 128 texels a side).
constexpr int kPrefilterSamples = 128;
// Levels of the prefiltered chain: roughness 0, 0.25, 0.5, 0.75, 1. The smallest
// must still hold the roughest lobe, which spans a face: at least 8 texels a side.
constexpr int kMaxLevels = 5;
constexpr int kSmallestLevel = 8;

// Level 0 of the cube map, read back as RGB floats, faces in GL's order.
std::vector<glm::vec3> readCubeLevel0(const gl::Texture& cube, int size) {
  std::vector<glm::vec3> texels(size_t(6 * size * size));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(cube.id(), 0, GL_RGB, GL_FLOAT, GLsizei(texels.size() * sizeof(glm::vec3)), texels.data());
  return texels;
}

int prefilterLevels(int size) {
  int levels = 1;
  while (levels < kMaxLevels && (size >> levels) >= kSmallestLevel) ++levels;
  return levels;
}

}  // namespace

gl::Texture makeCubeMap(int size, int levels) {
  if (levels <= 0) levels = std::bit_width(unsigned(size));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
  glTextureStorage2D(id, levels, GL_RGBA16F, size, size);
  gl::Texture cube = gl::Texture::adopt(id, size, size);
  cube.parameter(GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  cube.parameter(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  cube.parameter(GL_TEXTURE_MAX_LEVEL, levels - 1);
  // Lookups near a face's edge blend across it, not clamp to it.
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  return cube;
}

Result<EnvironmentLighting> EnvironmentLighting::create(const std::string& shaderDir, const gl::Texture& environment,
                                                        int size, Ambient ambient) {
  EnvironmentLighting lighting;
  lighting.size_ = size;
  static const SplitSumTable table = makeSplitSumTable(kSplitSumSize, kSplitSumSamples);
  lighting.splitSum_ = gl::Texture::table(GL_RGBA16F, GL_RGB, table.size, &table.texels[0].x);
  lighting.sh_ = projectIrradiance(readCubeLevel0(environment, size), size);
  if (ambient == Ambient::Ibl) {
    if (auto s = lighting.prefilter(shaderDir, environment, size); !s) return s.error();
  }
  return lighting;
}

// Level 0 is the environment itself (roughness 0: a mirror); each further level
// convolves the environment's full chain with the GGX lobe of its roughness.
Status EnvironmentLighting::prefilter(const std::string& shaderDir, const gl::Texture& environment, int size) {
  auto program = gl::Program::build(shaderDir, {{GL_COMPUTE_SHADER, "ibl_prefilter.comp"}});
  if (!program) return program.error();
  levels_ = prefilterLevels(size);
  prefiltered_ = makeCubeMap(size, levels_);
  glCopyImageSubData(environment.id(), GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, prefiltered_.id(), GL_TEXTURE_CUBE_MAP, 0, 0,
                     0, 0, size, size, 6);
  program->use();
  program->set("u_samples", kPrefilterSamples);
  program->set("u_sourceSize", float(size));
  environment.bind(gl::binding::kIblSource);
  for (int level = 1; level < levels_; ++level) {
    const int levelSize = size >> level;
    program->set("u_size", levelSize);
    program->set("u_roughness", float(level) / float(levels_ - 1));
    glBindImageTexture(gl::binding::kIblLevelImage, prefiltered_.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(GLuint((levelSize + 7) / 8), GLuint((levelSize + 7) / 8), 6);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  return Ok{};
}

void EnvironmentLighting::bind() const {
  splitSum_.bind(gl::binding::kSplitSum);
  if (prefiltered_) prefiltered_.bind(gl::binding::kPrefiltered);
}

std::string EnvironmentLighting::describe() const {
  std::ostringstream out;
  out << "brdf-lut(" << kSplitSumSize << "x" << kSplitSumSize << ") sh9(from cube " << size_ << ")";
  if (prefiltered_) {
    out << " prefiltered(cube " << size_ << ", " << levels_ << " levels " << size_ << ".." << (size_ >> (levels_ - 1))
        << ", " << kPrefilterSamples << " ggx samples)";
  }
  return out.str();
}

}  // namespace engine
