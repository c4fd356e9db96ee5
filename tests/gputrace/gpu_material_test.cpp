// The GPU tracers' material at a hit (shaders/rt/material_at.glsl's rtMaterialAt)
// against RtScene::materialAt, case by case through EGL and OSMesa: every texture a
// material reads (base colour, metallic-roughness, emissive, each of glTF's layer
// slots, the terrain's layers), vertex colours and the anisotropy's orientation. The
// images (gpu_trace_test.cpp, gpu_path_test.cpp) cannot see a layer texture read
// from the wrong channel where the image barely depends on it (a thickness that
// only says "a volume"); this sees it at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "../support/gl_test.h"
#include "../support/random_draws.h"
#include "../support/rt_textured.h"
#include "core/brdf.h"
#include "gl/bindings.h"
#include "gl/resources.h"
#include "gl/shader.h"
#include "gputrace/gpu_materials.h"
#include "gputrace/gpu_tracer_impl.h"
#include "gputrace/gpu_layout.h"
#include "gputrace/gpu_textures.h"

using namespace engine;
using engine::test::GlTest;

namespace {

struct MaterialCase {
  glm::ivec4 material;
  glm::vec4 uv, nsFootprint, dpdu, dpdv, color;
};

// support/rt_textured.h's textured room (base colour, emissive and metallic-roughness
// maps, every wrap mode, a transformed second uv set, the terrain's layers) with
// glTF's layers on five materials and a texture in every layer slot the tracers
// read: the red wall's sheen and coat, the white walls' film, the metal sphere's
// coat, the blue volume's specular weight and colour, transmission and thickness,
// and the grid's anisotropy.
rt::RtScene layeredTexturedRoom() {
  rt::RtScene scene = test::texturedRoom([](SceneDesc& desc) {
    test::layeredMaterials(desc);
    desc.materials[5].layers.specular = 0.8f;
    desc.materials[5].layers.specularColor = glm::vec3(1.0f, 0.7f, 0.9f);
    desc.materials[5].layers.ior = 1.7f;
    desc.materials[0].layers.iridescenceThicknessMin = 150.0f;
    desc.materials[8].layers.anisotropy = 0.8f;
    desc.materials[8].layers.anisotropyRotation = 0.5f;
  });
  test::addLayerTextures(scene);
  test::addLayerTexture(scene, 1, TextureSlot::Clearcoat, 5, 9);
  test::addLayerTexture(scene, 8, TextureSlot::Anisotropy, 5, 4);
  return scene;
}

// Random hits on every material: uvs far outside [0, 1], footprints from none to
// many texels (each mipmap level, and the blends between them), any shading normal
// (the terrain's slope), any uv gradient, heights across the terrain's range,
// vertex colours with alpha.
std::vector<MaterialCase> randomHits(int materials, int perMaterial, std::mt19937& rng) {
  std::uniform_real_distribution<float> uv(-3.0f, 3.0f), unit(0.0f, 1.0f), exponent(-12.0f, 1.0f), length(0.1f, 4.0f);
  std::vector<MaterialCase> cases;
  for (int m = 0; m < materials; ++m) {
    for (int k = 0; k < perMaterial; ++k) {
      MaterialCase c;
      c.material = glm::ivec4(m, 0, 0, 0);
      const float u0 = uv(rng), v0 = uv(rng), u1 = uv(rng), v1 = uv(rng);
      c.uv = glm::vec4(u0, v0, u1, v1);
      const float footprint = k % 8 == 0 ? 0.0f : std::exp2(exponent(rng));
      c.nsFootprint = glm::vec4(test::randomUnitVector(rng), footprint);
      const float height = unit(rng) * 0.7f;
      const glm::vec3 u = test::randomUnitVector(rng);
      c.dpdu = glm::vec4(u * length(rng), height);
      const glm::vec3 v = test::randomUnitVector(rng);
      c.dpdv = glm::vec4(v * length(rng), 0.0f);
      const float r = unit(rng), g = unit(rng), b = unit(rng), a = unit(rng);
      c.color = k % 2 == 0 ? glm::vec4(1.0f) : glm::vec4(r, g, b, a);
      cases.push_back(c);
    }
  }
  return cases;
}

std::vector<gpurt::GpuMaterial> gpuMaterialsAt(const rt::RtScene& scene, const std::vector<MaterialCase>& cases) {
  const rt::GpuTextureSet textures = rt::flattenTextures(scene);
  const std::vector<gpurt::GpuMaterial> materials = gpurt::materialsOf(scene, textures);
  auto program = gl::Program::build(test::shaderDir(), {{GL_COMPUTE_SHADER, "test/rt_material_eval.comp"}},
                                    gpurt::detail::traceDefines(rt::flattenScene(scene), &scene));
  EXPECT_TRUE(program) << program.error().message;
  if (!program) return {};
  const gl::Buffer materialBuffer = gpurt::detail::storage(materials);
  const gl::Buffer textureBuffer = gpurt::detail::storage(textures.textures);
  const gl::Buffer texelBuffer = gpurt::detail::storage(textures.texels);
  const gl::Buffer in = gpurt::detail::storage(cases);
  const gl::Buffer out = gl::Buffer::create(cases.size() * sizeof(gpurt::GpuMaterial));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtMaterials, materialBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtTextures, textureBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtTexels, texelBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtInput, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl::binding::kRtOutput, out.id());
  program->use();
  glUniform1ui(program->location("u_count"), GLuint(cases.size()));
  glDispatchCompute(GLuint((cases.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<gpurt::GpuMaterial> gpu(cases.size());
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(gpu.size() * sizeof(gpurt::GpuMaterial)), gpu.data());
  return gpu;
}

// Every value rtMaterialAt changes, as (CPU, GPU) pairs, by name, and how much a
// last-bit difference of the inputs may move it (1: not more than itself).
struct Field {
  const char* name;
  float cpu, gpu;
  float conditioning = 1.0f;
};

std::vector<Field> fieldsOf(const rt::HitMaterial& c, const gpurt::GpuMaterial& g) {
  std::vector<Field> f;
  const auto add3 = [&f](const char* name, const glm::vec3& a, const glm::vec4& b, float conditioning = 1.0f) {
    for (int i = 0; i < 3; ++i) f.push_back(Field{name, a[i], b[i], conditioning});
  };
  add3("albedo", c.albedo, g.colorAmbient);
  add3("emission", c.emission, g.emission);
  add3("dielectric f0", c.dielectricF0, g.dielectric);
  add3("sheen colour", c.sheenColor, g.sheenColorFilmIor);
  // The stretch t d.x + b d.y is normalised: a short direction d (an anisotropy
  // texel near 0.5 in R and G) magnifies the rounding of GLSL's sin and cos of its
  // turn by 1 / |d|.
  const float strength = c.anisotropy > 0.0f ? c.anisotropy : 0.0f;
  const float d = glm::length(brdf::anisotropyDirection(c.anisotropyDirection, c.anisotropyRotation));
  add3("anisotropy direction", strength > 0.0f ? c.anisotropyT : glm::vec3(0.0f), g.anisotropy,
       1.0f / std::max(d, 1e-3f));
  f.insert(f.end(), {Field{"metallic", c.metallic, g.metallicRoughnessUnlit.x},
                     Field{"roughness", c.roughness, g.metallicRoughnessUnlit.y},
                     Field{"specular", c.specular, g.diffuseSpecularShininessReflection.y},
                     Field{"dielectric f90", c.dielectricF90, g.dielectric.w},
                     Field{"clearcoat", c.clearcoat, g.coatSheen.x},
                     Field{"clearcoat roughness", c.clearcoatRoughness, g.coatSheen.y},
                     Field{"sheen roughness", c.sheenRoughness, g.coatSheen.z},
                     Field{"iridescence", c.iridescence, g.coatSheen.w},
                     Field{"iridescence thickness / 1000 nm", c.iridescenceThickness / 1000.0f, g.film.x / 1000.0f},
                     Field{"transmission", c.transmission, g.transmission.x},
                     Field{"thickness", c.thickness, g.transmission.z},
                     Field{"anisotropy", strength, g.anisotropy.w}});
  return f;
}

class GpuMaterialAt : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(GpuMaterialAt);

// 11 materials x 3000 random hits (randomHits). Limit: each value within 2e-5 of the
// CPU's (colours, factors and f0 are at most about 1; the film's thickness is
// compared in micrometres; the anisotropy's direction relative to its conditioning,
// fieldsOf): a texel read through the GPU's own log2 for the level of detail, or a
// direction through its sin, cos and sqrt, may round otherwise in the last bits; a
// texture read in the wrong channel, from the wrong uv set or at the wrong level is
// off by tenths (a coat, a thickness or a sheen's roughness read from another
// channel: 0.4-0.8; no specular tint: 0.04). Measured on llvmpipe: 1.25e-7 at most.
// Another draw of hits had 4 anisotropic ones whose direction was 1e-6 to 1.7e-5 off
// where |d| = 0.006: 9.5e-8 after its conditioning, which is why it is there.
TEST_P(GpuMaterialAt, IsTheCpusMaterialAtEveryHit) {
  std::mt19937 rng(20261204);
  const rt::RtScene scene = layeredTexturedRoom();
  const int materials = int(scene.materials().size());
  ASSERT_GE(materials, 10);
  const std::vector<MaterialCase> cases = randomHits(materials, 3000, rng);
  const std::vector<gpurt::GpuMaterial> gpu = gpuMaterialsAt(scene, cases);
  ASSERT_EQ(gpu.size(), cases.size());
  double worst = 0.0;
  int off = 0, anisotropic = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const MaterialCase& c = cases[i];
    const rt::HitMaterial cpu = scene.materialAt(c.material.x, rt::HitUv(glm::vec2(c.uv), glm::vec2(c.uv.z, c.uv.w), c.color),
                                                 c.nsFootprint.w, double(c.dpdu.w), glm::vec3(c.nsFootprint),
                                                 glm::vec3(c.dpdu), glm::vec3(c.dpdv));
    anisotropic += cpu.anisotropy > 0.0f ? 1 : 0;
    for (const Field& f : fieldsOf(cpu, gpu[i])) {
      const double error = std::abs(double(f.cpu) - double(f.gpu)) / double(f.conditioning);
      worst = std::max(worst, error);
      if (error > 2e-5 && off++ < 10) {
        ADD_FAILURE() << "material " << c.material.x << ", hit " << i << ": " << f.name << " CPU " << f.cpu << ", GPU "
                      << f.gpu;
      }
    }
  }
  EXPECT_EQ(off, 0);
  EXPECT_GT(anisotropic, 1000);
  std::printf("gpu material at %zu hits on %d materials: largest difference %.3g, %d values off, %d anisotropic\n",
              cases.size(), materials, worst, off, anisotropic);
}

}  // namespace
