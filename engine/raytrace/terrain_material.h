#pragma once
// The terrain's layered material for the ray tracer, as shaders/terrain.frag shades
// it: grass, rock and snow images (the bytes the terrain renderer uploads, made by
// terrain/materials.h), each sampled at two scales, blended per hit by the height
// above the terrain origin and the slope of the shading normal, and the roughness
// and classic highlight blended with the same weights: the rasterizer's text,
// shaders/common/terrain_layers.glsl (terrain::terrainLayersOf).
#include <array>

#include <glm/glm.hpp>

#include "raytrace/texture.h"

namespace engine::rt {

struct TerrainLayerSample {
  glm::vec3 albedo{0.0f};  // linear
  float roughness = 1.0f;
  float specular = 0.0f;   // classic highlight weight
};

class RtTerrainMaterial {
 public:
  // `originY`: world height of the terrain origin; `heightScale`: terrain.frag's
  // u_heightScale (the terrain's highest sample above its origin, at least 1e-3).
  RtTerrainMaterial(double originY, float heightScale);

  // At layer uv `uv` (terrain.vert's v_uv) with `footprint` (RtTexture::sample's),
  // world height `y` and unit shading normal y component `normalY`.
  TerrainLayerSample sample(glm::vec2 uv, float footprint, double y, float normalY) const;

  // What the GPU tracer copies (gputrace/gpu_textures.h).
  const std::array<RtTexture, 3>& layers() const { return layers_; }
  double originY() const { return originY_; }
  float heightScale() const { return heightScale_; }

 private:
  std::array<RtTexture, 3> layers_;  // grass, rock, snow
  double originY_ = 0.0;
  float heightScale_ = 1.0f;
};

}  // namespace engine::rt
