#pragma once
// A scene file's terrain block as terrain settings: the one conversion that the
// rasterizer and the ray tracer share, so both build the same field.
#include "asset/scene_desc.h"
#include "terrain/terrain.h"

namespace engine::terrain {

inline TerrainSettings settingsFromScene(const TerrainDesc& desc) {
  TerrainSettings settings;
  settings.heightmap = desc.heightmap;
  settings.seed = desc.seed;
  settings.size = desc.size;
  settings.spacing = desc.spacing;
  settings.heightScale = desc.heightScale;
  settings.origin = desc.origin;
  return settings;
}

}  // namespace engine::terrain
