#pragma once
// The scene's materials as the GPU integrators read them: rt/materials.glsl's
// RtMaterial, std430. Each is RtScene::baseMaterial (a MaterialDesc's own weights and
// layers) with what RtScene::materialAt changes at a hit: texture indices, alpha,
// the terrain's layers.
#include <vector>

#include <glm/glm.hpp>

#include "gputrace/gpu_textures.h"
#include "raytrace/rt_scene.h"

namespace engine::gpurt {

struct GpuMaterial {
  glm::vec4 colorAmbient;
  glm::vec4 diffuseSpecularShininessReflection;
  glm::vec4 metallicRoughnessUnlit;
  glm::vec4 emission;
  glm::vec4 dielectric;  // f0, f90
  glm::ivec4 textures;   // base colour, metallic-roughness, emissive, terrain (-1 none)
  glm::vec4 surface;     // texture scale, reads uv
  glm::vec4 alpha;       // mode, factor, cutoff, single-sided
  glm::vec4 coatSheen;   // clearcoat, clearcoatRoughness, sheenRoughness, iridescence
  glm::vec4 sheenColorFilmIor;
  glm::vec4 film;        // iridescenceThickness
  glm::vec4 transmission;  // transmission, ior, thickness, attenuationDistance
  glm::vec4 attenuation;   // attenuationColor
  glm::vec4 anisotropy;    // anisotropy, anisotropyRotation
  glm::ivec4 terrainLayers;              // grass, rock, snow: texture indices
  glm::dvec2 terrainOriginYHeightScale;  // RtTerrainMaterial's
  // glTF's layer textures (MaterialExtras::layerTextures: TextureSlot::Specular on,
  // -1 none), and what applying them takes from MaterialDesc::layers.
  glm::ivec4 layerTextures[3];
  glm::vec4 specularLayer;   // specularColor, specular
  glm::vec4 filmRange;       // iridescenceThicknessMin, Max
  glm::dvec2 reflectance;    // x: MaterialLayers::reflectance()
};
static_assert(sizeof(GpuMaterial) == 352);

// `textures`: where each terrain's layers are (rt::flattenTextures of the scene).
std::vector<GpuMaterial> materialsOf(const rt::RtScene& scene, const rt::GpuTextureSet& textures);

}  // namespace engine::gpurt
