#pragma once
// Shared helpers for the terrain tests: cameras and small terrains.
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "terrain/lod.h"
#include "terrain/terrain.h"

namespace engine::terrain::test {

inline LodCamera makeCamera(const glm::dvec3& position, const glm::dvec3& target,
                            int width = 1280, int height = 720, double fovYDegrees = 60.0) {
  LodCamera c;
  c.position = position;
  c.fovY = glm::radians(fovYDegrees);
  c.viewportHeight = height;
  const glm::mat4 projection = glm::perspective(float(c.fovY), float(width) / float(height), 0.5f, 100000.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(target - position), glm::vec3(0, 1, 0));
  c.viewProjection = projection * view;
  return c;
}

// selectLod once every block near enough to set one of the view's ranges has its
// errors measured: the view's settled selection, as a renderer's is after a few
// frames.
inline LodSelection settledSelection(const Terrain& t, const LodCamera& camera, double pixels) {
  measureBlocks(t, camera, pixels, SIZE_MAX);
  return selectLod(t, camera, pixels);
}

inline TerrainSettings noiseSettings(double size, double heightScale, glm::dvec3 origin = glm::dvec3(0.0)) {
  TerrainSettings s;
  s.seed = 7;
  s.size = size;
  s.spacing = 1.0;
  s.heightScale = heightScale;
  s.origin = origin;
  return s;
}

}  // namespace engine::terrain::test
