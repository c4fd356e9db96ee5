#pragma once
// KHR_materials_sheen's albedo scaling needs the white sheen's directional albedo
// E(N.V, sheen roughness): the integral of brdf.glsl's sheenBrdf times N.L over the
// hemisphere. The rasterizer samples it as a texture (render/model_renderer.cpp
// uploads this table), the tracers look it up here with the same bilinear filter, so
// every renderer dims the base under a sheen by the same amount.
//
// glTF's sheen (Estevez and Kulla's Charlie distribution with their fitted
// visibility, clamped at 1) is not energy-conserving at grazing views: E exceeds 1
// below N.V of about 0.04 at low roughness (1.36 at N.V 0.02, roughness 0.05). The
// scaling is kept at 0 or above, so the base never subtracts light there.
#include <vector>

namespace engine {

struct SheenTable {
  int size = 0;
  // Texel (i, j) at sqrt(N.V) = i / (size - 1), roughness j / (size - 1) (brdf.glsl's
  // sheenTableCoord); row-major from row 0.
  std::vector<float> texels;
  // Bilinear at sheenTableCoord: GL_LINEAR, as the rasterizer samples the uploaded
  // table.
  float lookup(float nDotV, float roughness) const;
};

// E at one N.V and roughness, by the midpoint rule over `steps` x `steps` cells of
// the hemisphere (sqrt(cos theta), and phi over the half the lobe mirrors).
float sheenAlbedoEntry(float nDotV, float roughness, int steps);

SheenTable makeSheenTable(int size, int steps);

// The engine's table (SHEEN_TABLE_SIZE a side, 48 x 48 cells a texel: within 0.1 %
// of a 2048 x 2048 rule), computed on first use (0.2 s).
const SheenTable& sheenTable();

}  // namespace engine
