// HitMaterial::atView on the GPU (raytrace/rt_scene.h): common/view_layers.glsl's
// terms of glTF's layers that depend on the view, for a material as rtMaterialAt
// gives it, with the sheen's albedo from its table. After rt/math.glsl,
// rt/materials.glsl and common/brdf.glsl, and after rtEnv is declared (the sheen's
// table lies in it, at u_sheenTable).
#include "common/view_layers.glsl"

// The sheen's directional albedo table (core/sheen_table.h, SHEEN_TABLE_SIZE a side),
// looked up as SheenTable::lookup does.
uniform int u_sheenTable;

float sheenTableLookup(float nDotV, float roughness) {
  int size = int(SHEEN_TABLE_SIZE);
  precise vec2 x = sheenTableCoord(nDotV, roughness) * float(size) - vec2(0.5);
  int x0 = clamp(int(floor(x.x)), 0, size - 1), y0 = clamp(int(floor(x.y)), 0, size - 1);
  int x1 = min(x0 + 1, size - 1), y1 = min(y0 + 1, size - 1);
  precise float wx = x.x - float(x0), wy = x.y - float(y0);
  float a = rtEnv[u_sheenTable + y0 * size + x0], b = rtEnv[u_sheenTable + y0 * size + x1];
  float c = rtEnv[u_sheenTable + y1 * size + x0], d = rtEnv[u_sheenTable + y1 * size + x1];
  precise float bottom = a + (b - a) * wx;
  precise float top = c + (d - c) * wx;
  precise float r = bottom + (top - bottom) * wy;
  return r;
}

// For the unit shading normal n at N.V = nDotV, of a material as rtMaterialAt gives it
// (m.anisotropy: xyz the stretch in the world, w its strength).
ViewLayers rtViewLayers(RtMaterial m, vec3 n, float nDotV) {
  vec3 sheenColor = m.sheenColorFilmIor.xyz;
  float sheenAlbedo = sheenColor != vec3(0.0) ? sheenTableLookup(nDotV, m.coatSheen.z) : 0.0;
  return viewLayersOf(n, nDotV, sheenAlbedo, sheenColor, m.anisotropy.xyz, m.anisotropy.w, m.coatSheen.w,
                      m.sheenColorFilmIor.w, m.film.x, m.dielectric.xyz, m.colorAmbient.xyz, m.metallicRoughnessUnlit.x);
}
