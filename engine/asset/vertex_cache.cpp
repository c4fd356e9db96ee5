#include "asset/vertex_cache.h"

#include <meshoptimizer.h>

namespace engine {

std::vector<std::uint32_t> orderForVertexCache(std::span<const std::uint32_t> indices, std::size_t vertexCount) {
  std::vector<std::uint32_t> out(indices.size());
  if (!indices.empty()) meshopt_optimizeVertexCache(out.data(), indices.data(), indices.size(), vertexCount);
  return out;
}

bool mayReorderTriangles(const ModelData& model, const PrimitiveData& primitive) {
  if (!isIndexedTriangleList(primitive)) return false;
  const int material = primitive.material;
  return material < 0 || material >= int(model.materials.size()) ||
         model.materials[std::size_t(material)].alphaMode != AlphaMode::Blend;
}

}  // namespace engine
