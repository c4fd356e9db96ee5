#include "render/terrain_cull.h"

#include <glm/glm.hpp>

namespace engine {

terrain::HeightRange patchHeights(const terrain::Terrain& terrain, const terrain::LodPatch& patch) {
  const glm::ivec2 quarter = terrain::patchPageOrigin(patch) / terrain::kPatchQuads;
  return terrain.page(patch.node)->patchRanges[size_t(quarter.x + 2 * quarter.y)];
}

cull::Cluster terrainPatchBox(const terrain::Terrain& terrain, const terrain::LodSelection& selection,
                              const terrain::LodPatch& patch, std::uint32_t indexCount) {
  const auto relative = [&selection](glm::ivec2 g) {
    const glm::ivec2 clamped = glm::min(g, selection.cells);
    return (glm::dvec2(clamped - selection.cameraCell) - glm::dvec2(selection.cameraFraction)) *
           double(selection.spacing);
  };
  const int side = terrain::kPatchQuads << patch.level;
  const terrain::HeightRange h = patchHeights(terrain, patch);
  const glm::dvec2 a = relative({patch.gx, patch.gz}), b = relative({patch.gx + side, patch.gz + side});
  return {glm::vec3(glm::dvec3(a.x, double(h.min) - selection.cameraHeight, a.y)), 0,
          glm::vec3(glm::dvec3(b.x, double(h.max) - selection.cameraHeight, b.y)), indexCount};
}

std::size_t removeHiddenPatches(const terrain::Terrain& terrain, terrain::LodSelection& selection,
                                const std::vector<cull::ScreenQuad>& quads, const glm::dmat4& viewProjection,
                                glm::dvec2 viewport, double pixelMargin) {
  if (quads.empty()) return 0;
  const auto hidden = [&](const terrain::LodPatch& patch) {
    const cull::Cluster box = terrainPatchBox(terrain, selection, patch, 0);
    return std::any_of(quads.begin(), quads.end(), [&](const cull::ScreenQuad& q) {
      return cull::hidesBox(q, glm::dvec3(box.lo), glm::dvec3(box.hi), viewProjection, viewport, pixelMargin);
    });
  };
  return std::erase_if(selection.patches, hidden);
}

}  // namespace engine
