// An indexed triangle list drawn in its runs (asset/vertex_runs.h, drawMesh): on
// llvmpipe every vertex of its buffers is shaded exactly once, fewer times than
// one draw of the same triangles shades them, and the pixels are the same.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/gl_test.h"
#include "asset/gltf_loader.h"
#include "gl/shader.h"
#include "render/mesh.h"
#include "render/model_renderer.h"
#include "render/render_target.h"

using namespace engine;
using engine::test::GlTest;

namespace {

// ARB_pipeline_statistics_query's counter (core in GL 4.6; glad's 4.5 headers lack it).
constexpr GLenum kVertexShaderInvocations = 0x82F0;

bool hasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
  return false;
}

// Vertex shader runs of `draw`.
template <typename Draw>
GLuint64 invocationsOf(Draw draw) {
  GLuint query = 0;
  glGenQueries(1, &query);
  glBeginQuery(kVertexShaderInvocations, query);
  draw();
  glEndQuery(kVertexShaderInvocations);
  GLuint64 count = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &count);
  glDeleteQueries(1, &query);
  return count;
}

// One draw of all of `prim`'s triangles from its 32-bit indices, as before runs.
void drawWhole(const GpuPrimitive& prim) {
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, prim.buffers[size_t(prim.sources.indices)].id());
  glDrawElements(GL_TRIANGLES, prim.indexCount, GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, prim.buffers[size_t(prim.sources.runIndices)].id());
}

// The mesh's bounds seen from the front, filling the view.
glm::mat4 framing(const PrimitiveData& data) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : data.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 center = (lo + hi) * 0.5f;
  const float radius = glm::length(hi - lo) * 0.5f;
  return glm::perspective(glm::radians(45.0f), 1.0f, radius * 0.5f, radius * 5.0f) *
         glm::lookAt(center + glm::vec3(0.3f, 0.2f, 1.0f) * (2.5f * radius), center, glm::vec3(0, 1, 0));
}

struct Drawn {
  Image image;
  GLuint64 invocations = 0;  // vertex shader runs
};

Drawn render(const gl::Program& program, const glm::mat4& viewProjection, const std::function<void()>& draw) {
  auto target = RenderTarget::create(256, 256, 1);
  EXPECT_TRUE(target.ok());
  target->bind();
  glViewport(0, 0, 256, 256);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  program.use();
  program.set("u_viewProjection", viewProjection);
  const GLuint64 invocations = invocationsOf(draw);
  glDisable(GL_DEPTH_TEST);
  return {target->readPixels(), invocations};
}

class VertexRunsGl : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN(VertexRunsGl);

TEST_P(VertexRunsGl, EachVertexShadedOnceAndTheSamePixels) {
  if (!hasExtension("GL_ARB_pipeline_statistics_query")) GTEST_SKIP() << "no pipeline statistics query";
  auto program = gl::Program::build(test::shaderDir(), {{GL_VERTEX_SHADER, "test/vertex_runs.vert"},
                                                        {GL_FRAGMENT_SHADER, "test/vertex_runs.frag"}});
  ASSERT_TRUE(program.ok()) << program.error().message;
  const std::string shared = std::string(ENGINE_SOURCE_DIR) + "/../shared/";
  int primitives = 0;
  for (const std::string& path :
       {std::string(ENGINE_SOURCE_DIR) + "/assets/models/character.gltf",
        shared + "conformance/assets/CesiumMan/glTF-Binary/CesiumMan.glb",
        shared + "gltf-samples/DamagedHelmet/glTF-Binary/DamagedHelmet.glb"}) {
    if (!std::filesystem::exists(path)) continue;
    auto model = loadGltf(path);
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto gpu = GpuModel::upload(*model);
    ASSERT_TRUE(gpu.ok()) << gpu.error().message;
    for (std::size_t m = 0; m < model->meshes.size(); ++m) {
      for (std::size_t p = 0; p < model->meshes[m].primitives.size(); ++p) {
        const GpuPrimitive& prim = gpu->meshes()[m][p];
        ASSERT_FALSE(prim.runs.empty()) << path << ": an indexed triangle list drawn whole";
        prim.vao.bind();
        const glm::mat4 viewProjection = framing(model->meshes[m].primitives[p]);
        const Drawn runs = render(*program, viewProjection, [&] { drawMesh(prim, GL_TRIANGLES, 0.0f, nullptr); });
        const Drawn whole = render(*program, viewProjection, [&] { drawWhole(prim); });
        std::printf("%s mesh %zu: %zu vertices, %d copies shaded %llu times in %zu runs, %llu times in one draw\n",
                    std::filesystem::path(path).filename().c_str(), m,
                    model->meshes[m].primitives[p].positions.size(), prim.vertexCount,
                    (unsigned long long)runs.invocations, prim.runs.size(), (unsigned long long)whole.invocations);
        EXPECT_EQ(runs.invocations, GLuint64(prim.vertexCount)) << path << " mesh " << m;
        EXPECT_LT(runs.invocations, whole.invocations) << path << " mesh " << m;
        EXPECT_EQ(runs.image.pixels, whole.image.pixels) << path << " mesh " << m;
        ++primitives;
      }
    }
  }
  EXPECT_GE(primitives, 1);
}

// The analytic shapes (render/mesh.h) too: the sphere every scene's spheres draw
// (9,216 triangles) and a plane of 16 x 16 cells.
TEST_P(VertexRunsGl, ShapesShadeEachVertexOnce) {
  if (!hasExtension("GL_ARB_pipeline_statistics_query")) GTEST_SKIP() << "no pipeline statistics query";
  auto program = gl::Program::build(test::shaderDir(), {{GL_VERTEX_SHADER, "test/vertex_runs.vert"},
                                                        {GL_FRAGMENT_SHADER, "test/vertex_runs.frag"}});
  ASSERT_TRUE(program.ok()) << program.error().message;
  for (const ShapeData& shape : {shapeForPrimitive(PrimitiveDesc{}), makePlane(2.0f, 16, 1.0f)}) {
    const GpuMesh mesh(shape);
    GLuint64 copies = 0;
    for (const VertexRun& run : mesh.runs()) copies += run.vertexCount;
    const Drawn drawn = render(*program, glm::mat4(0.4f), [&] { mesh.draw(); });
    std::printf("%zu vertices, %llu copies in %zu runs, shaded %llu times\n", shape.vertices.size(),
                (unsigned long long)copies, mesh.runs().size(), (unsigned long long)drawn.invocations);
    EXPECT_EQ(drawn.invocations, copies);
    // A grid's runs share a row of vertices at each edge: the sphere's rows of 97
    // at six edges, 1.12x.
    EXPECT_LE(copies, shape.vertices.size() * 115 / 100);
  }
}

}  // namespace
