// gputrace/gpu_textures.h and the layout's texture coordinates: what the GPU tracer
// samples is the CPU tracer's own data, texel for texel, at the indices the
// materials hold (the shaders' sampling is judged against the CPU's images in
// tests/gputrace/gpu_trace_test.cpp and gpu_path_test.cpp).
#include <gtest/gtest.h>

#include "../support/rt_textured.h"
#include "gputrace/gpu_layout.h"
#include "gputrace/gpu_textures.h"

namespace rt = engine::rt;

namespace {

void expectSameTexture(const rt::RtTexture& t, const rt::GpuTexture& g, const std::vector<glm::vec4>& texels) {
  ASSERT_EQ(g.info.x, t.levels());
  EXPECT_EQ(g.info.y, int(t.wrapS()));
  EXPECT_EQ(g.info.z, int(t.wrapT()));
  EXPECT_EQ(g.info.w, t.texCoord());
  for (int c = 0; c < 3; ++c) EXPECT_EQ(glm::vec3(g.transform[c]), t.uvTransform()[c]);
  EXPECT_EQ(g.transform[0].w, t.footprintScale());
  EXPECT_EQ(g.transform[1].w, t.transformed() ? 1.0f : 0.0f);
  for (int level = 0; level < t.levels(); ++level) {
    const glm::ivec4 l = g.level[level];
    ASSERT_EQ(glm::ivec2(l.y, l.z), t.levelSize(level));
    const std::vector<glm::vec4>& cpu = t.levelTexels(level);
    ASSERT_LE(std::size_t(l.x) + cpu.size(), texels.size());
    EXPECT_TRUE(std::equal(cpu.begin(), cpu.end(), texels.begin() + l.x)) << "level " << level;
  }
}

TEST(GpuTextures, AreTheCpusTexelsAtTheMaterialsIndices) {
  const rt::RtScene scene = engine::test::texturedRoom();
  ASSERT_TRUE(rt::fitsGpuTextures(scene));
  const rt::GpuTextureSet set = rt::flattenTextures(scene);
  ASSERT_EQ(set.textures.size(), scene.textures().size() + 3 * scene.terrains().size());
  for (std::size_t i = 0; i < scene.textures().size(); ++i) expectSameTexture(scene.textures()[i], set.textures[i], set.texels);
  ASSERT_EQ(set.terrains.size(), scene.terrains().size());
  for (std::size_t i = 0; i < scene.terrains().size(); ++i) {
    const rt::RtTerrainMaterial& terrain = scene.terrains()[i];
    for (int layer = 0; layer < 3; ++layer) {
      expectSameTexture(terrain.layers()[std::size_t(layer)], set.textures[std::size_t(set.terrains[i].layers[layer])],
                        set.texels);
    }
    EXPECT_EQ(set.terrains[i].originYHeightScale, glm::dvec2(terrain.originY(), double(terrain.heightScale())));
  }
}

// Each triangle's uvs (both sets) and colours in the layout's global order: the order the
// leaves' ids and GpuTriangle use.
TEST(GpuTextures, TrianglesCarryTheirMeshesUvsAndColours) {
  const rt::RtScene scene = engine::test::texturedRoom();
  const rt::GpuSceneLayout layout = rt::flattenScene(scene, 4);
  ASSERT_TRUE(layout.hasUvs);
  ASSERT_TRUE(layout.hasColors);
  ASSERT_EQ(layout.attributeSlots(), 6);
  ASSERT_EQ(layout.triangleAttributes.size(), 6 * layout.triangles.size());
  int withUvs = 0;
  for (int group = 0; group < scene.groupCount(); ++group) {
    const auto& meshOf = scene.groupTriangleMeshes(group);
    for (std::size_t t = 0; t < meshOf.size(); ++t) {
      const rt::RtMesh& mesh = scene.meshes()[meshOf[t]];
      const std::size_t first = 3 * (t - scene.meshFirstTriangle(int(meshOf[t])));
      const glm::vec4* g = &layout.triangleAttributes[6 * (layout.firstTriangle[std::size_t(group)] + t)];
      for (int v = 0; v < 3; ++v) {
        const std::uint32_t i = mesh.indices[first + std::size_t(v)];
        const glm::vec2 uv0 = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[i];
        const glm::vec2 uv1 = mesh.uvs1.empty() ? uv0 : mesh.uvs1[i];
        ASSERT_EQ(g[v], glm::vec4(uv0, uv1)) << "group " << group << " triangle " << t;
        ASSERT_EQ(g[3 + v], mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[i]);
      }
      withUvs += mesh.uvs.empty() ? 0 : 1;
    }
  }
  EXPECT_GT(withUvs, 1000);
  // Without a texture in the scene, no array (its boxes have uvs).
  EXPECT_TRUE(rt::flattenScene(engine::test::roomWithMeshes(), 4).triangleAttributes.empty());
}

}  // namespace
