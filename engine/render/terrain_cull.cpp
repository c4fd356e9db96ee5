#include "render/terrain_cull.h"

#include <glm/glm.hpp>

namespace engine {

cull::Cluster terrainPatchBox(const terrain::Terrain& terrain, const terrain::LodSelection& selection,
                              const terrain::LodPatch& patch, std::uint32_t indexCount) {
  const auto relative = [&selection](glm::ivec2 g) {
    const glm::ivec2 clamped = glm::min(g, selection.cells);
    return (glm::dvec2(clamped - selection.cameraCell) - glm::dvec2(selection.cameraFraction)) *
           double(selection.spacing);
  };
  const int side = terrain::kPatchQuads << patch.level;
  const terrain::HeightRange h = terrain.regionBounds(patch.gx, patch.gz, patch.gx + side, patch.gz + side);
  const glm::dvec2 a = relative({patch.gx, patch.gz}), b = relative({patch.gx + side, patch.gz + side});
  return {glm::vec3(glm::dvec3(a.x, double(h.min) - selection.cameraHeight, a.y)), 0,
          glm::vec3(glm::dvec3(b.x, double(h.max) - selection.cameraHeight, b.y)), indexCount};
}

}  // namespace engine
