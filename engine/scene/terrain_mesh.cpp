#include "scene/terrain_mesh.h"

#include "terrain/materials.h"
#include "terrain/terrain.h"

namespace engine {

namespace {

terrain::LodCamera lodCamera(const TerrainView& view) {
  terrain::LodCamera camera;
  camera.position = view.eye;
  camera.fovY = view.fovY;
  camera.viewportHeight = view.viewportHeight;
  camera.cull = view.cullViewProjection.has_value();
  if (camera.cull) camera.viewProjection = *view.cullViewProjection;
  camera.zeroToOneDepth = view.zeroToOneDepth;
  return camera;
}

}  // namespace

double terrainErrorTarget(const SceneDesc& desc, double override) {
  return override > 0.0 ? override : desc.terrain.errorPixels;
}

std::size_t measureTerrain(const terrain::Terrain& field, const TerrainView& view) {
  return terrain::measureBlocks(field, lodCamera(view), view.errorPixels);
}

terrain::LodSelection selectTerrain(const terrain::Terrain& field, const TerrainView& view) {
  return terrain::selectLodWithin(field, lodCamera(view), view.errorPixels, view.maxPages);
}

std::vector<TerrainPatchMesh> terrainPatchMeshes(const terrain::Terrain& field, const terrain::LodSelection& selection,
                                                 const glm::dvec3& eye) {
  // Layer uvs as terrain.vert makes them: camera-relative metres over the tile size
  // plus the rasterizer's offset (the far scale multiplies the whole uv, so the
  // offset must be the same).
  const glm::vec2 uvOffset = terrain::layerUvOffset(eye - field.origin());
  std::vector<TerrainPatchMesh> meshes;
  meshes.reserve(selection.patches.size());
  for (const auto& patch : selection.patches) {
    TerrainPatchMesh& mesh = meshes.emplace_back();
    for (const glm::vec3& v : terrain::patchVertices(field, selection, patch)) {
      mesh.positions.push_back(glm::vec3(glm::dvec3(v) + eye));
      mesh.uvs.push_back(glm::vec2(v.x, v.z) / terrain::kLayerTileMetres + uvOffset);
    }
    mesh.normals = terrain::patchNormals(field, selection, patch);
  }
  return meshes;
}

const std::vector<std::uint32_t>& terrainPatchIndices() {
  static const std::vector<std::uint32_t> indices = terrain::patchIndices();
  return indices;
}

}  // namespace engine
