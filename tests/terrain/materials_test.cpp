// The terrain's layer weights (terrain/materials.h, the twin of terrain.frag's
// layerWeights) at their extremes.
#include <gtest/gtest.h>

#include <cmath>

#include "terrain/materials.h"

using namespace engine::terrain;

namespace {

void expectWeights(const glm::vec3& w, const glm::vec3& expected) {
  EXPECT_NEAR(w.x, expected.x, 1e-6f);
  EXPECT_NEAR(w.y, expected.y, 1e-6f);
  EXPECT_NEAR(w.z, expected.z, 1e-6f);
}

}  // namespace

TEST(LayerWeights, FlatLowGroundIsGrass) {
  expectWeights(layerWeights(0.0f, 0.0f, 0.0f), {1, 0, 0});
  expectWeights(layerWeights(0.3f, 0.1f, 1.5f), {1, 0, 0});
}

TEST(LayerWeights, VerticalCliffIsRockAtAnyHeight) {
  for (float h : {0.0f, 0.5f, 0.9f, 1.0f}) expectWeights(layerWeights(h, 1.0f, 0.0f), {0, 1, 0});
}

TEST(LayerWeights, HighFlatGroundIsSnow) {
  expectWeights(layerWeights(1.0f, 0.0f, 0.0f), {0, 0, 1});
  expectWeights(layerWeights(0.8f, 0.1f, -0.5f), {0, 0, 1});
}

TEST(LayerWeights, TheJitterMovesTheSnowLine) {
  // At 0.63 the snow weight is partial; the texture's brightness pushes it either way.
  EXPECT_GT(layerWeights(0.63f, 0.0f, 1.5f).z, layerWeights(0.63f, 0.0f, -0.5f).z);
}

TEST(LayerWeights, SumToOneAndStayFiniteEverywhere) {
  for (float h : {-100.0f, -1.0f, 0.0f, 0.3f, 0.6f, 0.65f, 0.7f, 1.0f, 2.0f, 1e6f}) {
    for (float slope : {0.0f, 0.2f, 0.28f, 0.35f, 0.4f, 0.5f, 0.6f, 0.8f, 1.0f}) {
      for (float jitter : {-0.5f, 0.0f, 1.5f}) {
        const glm::vec3 w = layerWeights(h, slope, jitter);
        SCOPED_TRACE(testing::Message() << "height " << h << " slope " << slope << " jitter " << jitter);
        for (int c = 0; c < 3; ++c) {
          EXPECT_TRUE(std::isfinite(w[c]));
          EXPECT_GE(w[c], 0.0f);
          EXPECT_LE(w[c], 1.0f);
        }
        EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f);
      }
    }
  }
}
