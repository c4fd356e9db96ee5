// The path tracers' scattering, one text (shaders/common/bsdf.glsl) by two compilers:
// the GPU's GLSL build (rt/bsdf.glsl over the material buffer) against the C++ build
// (core/bsdf.h under raytrace/bsdf.h's Bsdf), case by case through EGL and OSMesa:
// the same f and pdf for a direction, and the same sample (direction, pdf, weight) for
// the same random numbers, over random materials with and without clear coat,
// sheen, thin film, transmission and anisotropy, random normals and directions. The path tracer's images
// (gpu_path_test.cpp) judge whole paths statistically and cannot see a lobe a few
// percent off; this sees it at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "../support/gl_test.h"
#include "../support/random_draws.h"
#include "gl/bindings.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "gputrace/gpu_materials.h"
#include "core/sheen_table.h"
#include "raytrace/bsdf.h"
#include "gputrace/gpu_textures.h"
#include "raytrace/rt_scene.h"

using namespace engine;
using engine::test::GlTest;

namespace {

struct BsdfCase {
  glm::ivec4 material;
  glm::vec4 n, wo, wi, u;
};
struct BsdfAnswer {
  glm::vec4 f, drawn, weight, shares;
};

using test::draw3;
using test::randomUnitVector;

// 48 materials: metallic-roughness with every mix of coat, sheen and film (and none),
// random colours, metalness and roughness down to 0.02; and a few classic ones.
rt::RtScene randomMaterials(std::mt19937& rng) {
  rt::RtScene scene;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int k = 0; k < 48; ++k) {
    MaterialDesc m;
    m.color = draw3(unit, rng);
    m.metallic = k % 3 == 0 ? 0.0f : unit(rng);
    m.roughness = 0.02f + 0.98f * unit(rng);
    m.diffuse = 0.5f + 0.5f * unit(rng);
    m.specular = k % 2 ? 0.3f * unit(rng) : 0.0f;
    m.shininess = 4.0f + 60.0f * unit(rng);
    m.reflection = k % 5 == 0 ? 0.5f * unit(rng) : 0.0f;
    if (k & 1) {
      m.layers.clearcoat = 0.2f + 0.8f * unit(rng);
      m.layers.clearcoatRoughness = 0.02f + 0.5f * unit(rng);
    }
    if (k & 2) {
      m.layers.sheenColor = draw3(unit, rng);
      m.layers.sheenRoughness = 0.05f + 0.95f * unit(rng);
    }
    if (k & 4) {
      m.layers.iridescence = 0.3f + 0.7f * unit(rng);
      m.layers.iridescenceIor = 1.2f + 0.6f * unit(rng);
      m.layers.iridescenceThicknessMax = 100.0f + 700.0f * unit(rng);
    }
    if (k & 8) m.layers.ior = 1.2f + 1.3f * unit(rng);
    if (k % 7 == 3) {
      m.layers.anisotropy = 0.2f + 0.8f * unit(rng);
      m.layers.anisotropyRotation = 6.0f * unit(rng);
    }
    if (k & 16) {
      m.layers.transmission = 0.3f + 0.7f * unit(rng);
      m.layers.thickness = k & 32 ? 0.0f : 0.5f;  // a thin wall, or a volume
    }
    scene.addMaterial(m);
  }
  return scene;
}

class GpuBsdf : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuBsdf);

// 49 materials (the scene's default and 48 random; 16 of them transmissive, thin
// walls and volumes, entered from either side; 7 anisotropic, stretched along a
// random direction as orientAnisotropy leaves it) x 1000 (normal, wo, wi, random numbers), wo and wi over the whole
// sphere (a third of them under the surface, which both must refuse alike).
// Limits: f and pdf within 1e-5 relative (the BRDF test's, for one evaluation) plus
// four times what they change by when wi or wo moves by a float's last bit (near the
// horizon, or at a sharp lobe's peak, a last-bit change of the GPU's half vector or
// frame is such a move: one bit of a wi 1.5e-5 off the horizon moves f by 2.4e-5);
// measured 0.33 of that. The samples, where both drew: directions within 1e-4
// absolute (measured 6.9e-6), pdf and weight within 1e-3 relative plus four times
// what a last-bit move of wo changes them by (measured 0.36 of that; a GGX peak of
// roughness 0.03 seen at grazing moves its pdf by 2e-3 relative). The same cases
// and figures from g++ and clang builds. Drawn or not must
// agree in all but 0.1 % (a direction at the horizon may fall either side).
TEST_P(GpuBsdf, TheShadersScatteringIsTheCpus) {
  std::mt19937 rng(20261204);
  const rt::RtScene scene = randomMaterials(rng);
  std::vector<gpurt::GpuMaterial> materials = gpurt::materialsOf(scene, rt::flattenTextures(scene));
  // An anisotropic material's stretch as rtMaterialAt leaves it oriented at a hit
  // (xyz the direction in the world, w the strength), the same on the CPU's side.
  std::vector<glm::vec3> stretch(materials.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].anisotropy.x <= 0.0f) continue;
    stretch[i] = randomUnitVector(rng);
    materials[i].anisotropy = glm::vec4(stretch[i], std::clamp(materials[i].anisotropy.x, 0.0f, 1.0f));
  }
  std::vector<BsdfCase> cases;
  std::uniform_real_distribution<float> unit(0.0f, 0.99999994f);
  for (int m = 0; m < int(materials.size()); ++m) {
    for (int k = 0; k < 1000; ++k) {
      const glm::vec3 n = randomUnitVector(rng);
      glm::vec3 wo = randomUnitVector(rng), wi = randomUnitVector(rng);
      if (k % 3 != 0 && glm::dot(wo, n) < 0.0f) wo = -wo;
      if (k % 3 != 0 && glm::dot(wi, n) < 0.0f) wi = -wi;
      cases.push_back(BsdfCase{glm::ivec4(m, m % 6 == 5 ? 0 : 1, k % 2, 0), glm::vec4(n, 0.0f), glm::vec4(wo, 0.0f),
                           glm::vec4(wi, 0.0f), glm::vec4(draw3(unit, rng), 0.0f)});
    }
  }
  std::vector<std::string> defines;
  auto program = gl::Program::build(test::shaderDir(), {{GL_COMPUTE_SHADER, "test/rt_bsdf_eval.comp"}}, defines);
  ASSERT_TRUE(program) << program.error().message;
  // The sheen table where rt/bsdf.glsl reads it: at u_sheenTable of the environment's buffer.
  const gl::Buffer tables = gl::Buffer::create(sheenTable().texels.size() * sizeof(float), sheenTable().texels.data());
  const gl::Buffer materialBuffer = gl::Buffer::create(materials.size() * sizeof(gpurt::GpuMaterial), materials.data());
  const gl::Buffer in = gl::Buffer::create(cases.size() * sizeof(BsdfCase), cases.data());
  const gl::Buffer out = gl::Buffer::create(cases.size() * sizeof(BsdfAnswer));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtEnvironment, tables.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtMaterials, materialBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtInput, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtOutput, out.id());
  program->use();
  program->set("u_sheenTable", 0);
  glUniform1ui(program->location("u_count"), GLuint(cases.size()));
  glDispatchCompute(GLuint((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<BsdfAnswer> gpu(cases.size());
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(gpu.size() * sizeof(BsdfAnswer)), gpu.data());

  const auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(a), 1e-6); };
  double worstValue = 0.0, worstDirection = 0.0, worstSample = 0.0;
  int drawnDiffer = 0, bothDrew = 0, nonZero = 0, transmitted = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const BsdfCase& c = cases[i];
    rt::HitMaterial m = scene.baseMaterial(c.material.x);
    m.anisotropyT = stretch[std::size_t(c.material.x)];
    m.anisotropy = std::clamp(m.anisotropy, 0.0f, 1.0f);
    const glm::vec3 n(c.n), wo(c.wo), wi(c.wi);
    const rt::Bsdf b = c.material.y ? rt::Bsdf::metallicRoughness(m, n, wo, c.material.z != 0) : rt::Bsdf::classic(m, n, wo);
    const glm::vec2 u(c.u);
    const glm::vec3 f = b.f(wi);
    const float pdf = b.pdf(wi);
    const BsdfAnswer& g = gpu[i];
    nonZero += f != glm::vec3(0.0f) ? 1 : 0;
    // How much f and the pdf move when wi or wo moves by a float's last bit (a
    // grazing direction makes them ill-conditioned: the GPU's half vector or frame,
    // rounded otherwise, is such a move): the limit is 1e-5 relative plus four of those.
    // Two moves across w: one in the plane with n (toward or off the horizon) and one
    // about n.
    const auto nudged = [&](const glm::vec3& w, float e) {
      const glm::vec3 about = glm::normalize(glm::cross(w, n + glm::vec3(0.1f, 0.2f, 0.3f)));
      const glm::vec3 across = e > 0.0f ? about : glm::normalize(glm::cross(w, about));
      return glm::normalize(w + std::abs(e) * across);
    };
    const auto bsdfAt = [&](const glm::vec3& o) {
      return c.material.y ? rt::Bsdf::metallicRoughness(m, n, o, c.material.z != 0) : rt::Bsdf::classic(m, n, o);
    };
    glm::vec4 moved(0.0f);
    for (const float e : {1.2e-7f, -1.2e-7f}) {
      const glm::vec3 w = nudged(wi, e);
      moved = glm::max(moved, glm::abs(glm::vec4(b.f(w), b.pdf(w)) - glm::vec4(f, pdf)));
      const rt::Bsdf other = bsdfAt(nudged(wo, e));
      moved = glm::max(moved, glm::abs(glm::vec4(other.f(wi), other.pdf(wi)) - glm::vec4(f, pdf)));
    }
    const glm::vec4 cpuValue(f, pdf), gpuValue(g.f);
    for (int k = 0; k < 4; ++k) {
      const double limit = 1e-5 + 4.0 * double(moved[k]) / std::max(std::abs(double(cpuValue[k])), 1e-6);
      worstValue = std::max(worstValue, relative(cpuValue[k], gpuValue[k]) / limit);
    }
    const rt::BsdfSample s = b.sample(u, c.u.z);
    if (s.drawn != (g.weight.w > 0.0f)) {
      ++drawnDiffer;
      continue;
    }
    if (!s.drawn) continue;
    ++bothDrew;
    ASSERT_EQ(s.delta, g.weight.w >= 2.0f) << "case " << i;
    ASSERT_EQ(s.transmitted, g.weight.w == 3.0f) << "case " << i;
    transmitted += s.transmitted ? 1 : 0;
    // The sample's pdf and weight get the same allowance for a last-bit move of wo.
    glm::vec4 sampleMoved(0.0f);
    for (const float e : {1.2e-7f, -1.2e-7f}) {
      if (const rt::BsdfSample o = bsdfAt(nudged(wo, e)).sample(u, c.u.z); o.drawn) {
        sampleMoved = glm::max(sampleMoved, glm::abs(glm::vec4(o.weight, o.pdf) - glm::vec4(s.weight, s.pdf)));
      }
    }
    const glm::vec4 cpuSample(s.weight, s.pdf), gpuSample(glm::vec3(g.weight), g.drawn.w);
    for (int k = 0; k < 4; ++k) {
      if (k < 3) worstDirection = std::max(worstDirection, double(std::abs(s.wi[k] - g.drawn[k])));
      const double limit = 1e-3 + 4.0 * double(sampleMoved[k]) / std::max(std::abs(double(cpuSample[k])), 1e-6);
      worstSample = std::max(worstSample, relative(cpuSample[k], gpuSample[k]) / limit);
    }
  }
  EXPECT_GT(nonZero, int(cases.size()) / 4);
  EXPECT_GT(bothDrew, int(cases.size()) / 2);
  EXPECT_GT(transmitted, int(cases.size()) / 50);
  EXPECT_LE(worstValue, 1.0);
  EXPECT_LE(worstDirection, 1e-4);
  EXPECT_LE(worstSample, 1.0);
  EXPECT_LE(drawnDiffer, int(cases.size()) / 1000);
  std::printf("gpu bsdf: %zu cases, %d both drew (%d through the surface), %d drawn by one only; worst f/pdf "
              "%.3g of its limit, sample direction %.3g, sample pdf/weight %.3g of its limit\n",
              cases.size(), bothDrew, transmitted, drawnDiffer, worstValue, worstDirection, worstSample);
}

}  // namespace
