// generateTangents (asset/tangents.h): the frame glTF expects on known layouts,
// orthogonal unit tangents on a curved mesh, and finite output from degenerate
// input (no uv area, zero normals, huge coordinates, bad indices).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "asset/tangents.h"

namespace engine {
namespace {

// A unit quad facing +z; uv (0,0) at the top-left as glTF lays images out, or
// mirrored left-right.
struct Quad {
  std::vector<glm::vec3> positions{{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
  std::vector<glm::vec3> normals = std::vector<glm::vec3>(4, glm::vec3(0, 0, 1));
  std::vector<glm::vec2> uvs{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<std::uint32_t> indices{0, 3, 1, 1, 3, 2};
  std::vector<glm::vec4> tangents() const { return generateTangents(positions, normals, uvs, indices); }
};

glm::vec3 bitangent(const glm::vec3& n, const glm::vec4& t) { return glm::cross(n, glm::vec3(t)) * t.w; }

void expectFiniteFrame(const glm::vec3& normal, const glm::vec4& t) {
  ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && std::isfinite(t.w));
  EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f);
  EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << t.w;
  const glm::vec3 n = glm::length(normal) > 0.0f ? glm::normalize(normal) : glm::vec3(0, 0, 1);
  EXPECT_NEAR(glm::dot(n, glm::vec3(t)), 0.0f, 1e-5f);
}

TEST(TangentsTest, TangentFollowsUAndBitangentPointsUpTheImage) {
  const Quad q;
  const auto t = q.tangents();
  ASSERT_EQ(t.size(), 4u);
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(glm::distance(glm::vec3(t[v]), glm::vec3(1, 0, 0)), 0.0f, 1e-6f) << v;
    EXPECT_EQ(t[v].w, 1.0f) << v;
    // glTF's v runs down the image; the map's +Y (up the image) is +y here.
    EXPECT_NEAR(glm::distance(bitangent(q.normals[v], t[v]), glm::vec3(0, 1, 0)), 0.0f, 1e-6f) << v;
  }
}

TEST(TangentsTest, MirroredUvFlipsTheHandedness) {
  Quad q;
  for (glm::vec2& uv : q.uvs) uv.x = 1.0f - uv.x;
  const auto t = q.tangents();
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(glm::distance(glm::vec3(t[v]), glm::vec3(-1, 0, 0)), 0.0f, 1e-6f) << v;
    EXPECT_EQ(t[v].w, -1.0f) << v;
    // The bitangent still points up the image.
    EXPECT_NEAR(glm::distance(bitangent(q.normals[v], t[v]), glm::vec3(0, 1, 0)), 0.0f, 1e-6f) << v;
  }
}

TEST(TangentsTest, OrthogonalToSmoothNormalsOnASphere) {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
  const int around = 24, down = 12;
  for (int j = 0; j <= down; ++j)
    for (int i = 0; i <= around; ++i) {
      const float theta = glm::pi<float>() * float(j) / float(down), phi = glm::two_pi<float>() * float(i) / float(around);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      positions.push_back(n * 2.0f);
      normals.push_back(n);
      uvs.push_back({float(i) / float(around), float(j) / float(down)});
    }
  for (int j = 0; j < down; ++j)
    for (int i = 0; i < around; ++i) {
      const std::uint32_t a = std::uint32_t(j * (around + 1) + i), b = a + std::uint32_t(around + 1);
      for (std::uint32_t k : {a, b, a + 1, a + 1, b, b + 1}) indices.push_back(k);
    }
  const auto t = generateTangents(positions, normals, uvs, indices);
  ASSERT_EQ(t.size(), positions.size());
  for (size_t v = 0; v < t.size(); ++v) {
    SCOPED_TRACE(v);
    expectFiniteFrame(normals[v], t[v]);
  }
  // Away from the poles u runs around the sphere: the tangent is the eastward
  // direction d(position)/d(phi), and the bitangent (up the image) points north.
  const size_t equator = size_t(down / 2 * (around + 1) + 3);
  const float phi = glm::two_pi<float>() * 3.0f / float(around);
  EXPECT_NEAR(glm::dot(glm::vec3(t[equator]), glm::vec3(std::cos(phi), 0.0f, -std::sin(phi))), 1.0f, 1e-3f);
  EXPECT_GT(bitangent(normals[equator], t[equator]).y, 0.99f);
}

TEST(TangentsTest, DegenerateInputGivesFiniteTangents) {
  // Every uv the same: no triangle says where u points.
  Quad same;
  for (glm::vec2& uv : same.uvs) uv = glm::vec2(0.5f);
  for (const glm::vec4& t : same.tangents()) expectFiniteFrame(glm::vec3(0, 0, 1), t);

  // Zero-length and non-unit normals, a zero-area triangle, huge coordinates.
  Quad odd;
  odd.normals = {glm::vec3(0.0f), glm::vec3(0, 0, 5), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)};
  odd.positions[2] = odd.positions[1];
  for (glm::vec3& p : odd.positions) p *= 1e30f;
  const auto t = odd.tangents();
  for (size_t v = 0; v < 4; ++v) {
    SCOPED_TRACE(v);
    expectFiniteFrame(odd.normals[v], t[v]);
  }

  // Indices past the vertices and a trailing partial triangle are skipped.
  Quad bad;
  bad.indices = {0, 3, 99, 1, 3, 2, 0};
  for (const glm::vec4& tangent : bad.tangents()) expectFiniteFrame(glm::vec3(0, 0, 1), tangent);

  // Missing uvs: nothing to build from, still one finite tangent per vertex.
  Quad none;
  none.uvs.clear();
  const auto fallback = none.tangents();
  ASSERT_EQ(fallback.size(), 4u);
  for (const glm::vec4& tangent : fallback) expectFiniteFrame(glm::vec3(0, 0, 1), tangent);
}

TEST(TangentsTest, NonIndexedTriangles) {
  const std::vector<glm::vec3> positions{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> normals(3, glm::vec3(0, 0, 1));
  // uv v runs down the image: the triangle's +y is up the image (v decreasing).
  const std::vector<glm::vec2> uvs{{0, 1}, {1, 1}, {0, 0}};
  const auto t = generateTangents(positions, normals, uvs, {});
  ASSERT_EQ(t.size(), 3u);
  for (const glm::vec4& tangent : t) {
    EXPECT_NEAR(glm::distance(glm::vec3(tangent), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(tangent.w, 1.0f);
  }
}

}  // namespace
}  // namespace engine
