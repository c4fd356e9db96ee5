// HitMaterial::atView on the GPU (raytrace/rt_scene.h): the terms of glTF's layers that
// depend on the view, worked out once per hit for the Whitted tracer's lights and
// ambient and for the path tracer's Bsdf alike, as both CPU tracers share them. Change
// both together. After rt/materials.glsl and common/brdf.glsl, and after rtEnv is
// declared (the sheen's table lies in it, at u_sheenTable).

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

struct RtViewLayers {
  float sheenAlbedo, sheenScale;    // the white sheen's albedo at N.V; what it leaves the base
  vec3 anisotropyT, anisotropyB;    // the stretch made orthogonal to n, and n x it
  float anisotropy;                 // 0 where there is no stretch to orient
  vec3 iridescenceF;                // the thin film's Fresnel at N.V
};

// For the unit shading normal n at N.V = nDotV, of a material as rtMaterialAt gives it
// (m.anisotropy: xyz the stretch in the world, w its strength).
RtViewLayers rtViewLayers(RtMaterial m, vec3 n, float nDotV) {
  RtViewLayers v;
  vec3 sheenColor = m.sheenColorFilmIor.xyz;
  v.sheenAlbedo = sheenColor != vec3(0.0) ? sheenTableLookup(nDotV, m.coatSheen.z) : 0.0;
  v.sheenScale = sheenScaling(sheenColor, v.sheenAlbedo);
  // HitMaterial::anisotropyTangent.
  v.anisotropyT = vec3(0.0);
  v.anisotropy = 0.0;
  if (m.anisotropy.w > 0.0) {
    precise vec3 t = m.anisotropy.xyz - n * rtDot(n, m.anisotropy.xyz);
    float len = sqrt(rtDot(t, t));
    if (len > 1e-6) {
      v.anisotropyT = t / len;
      v.anisotropy = m.anisotropy.w;
    }
  }
  v.anisotropyB = rtCross(n, v.anisotropyT);
  v.iridescenceF = vec3(0.0);
  if (m.coatSheen.w > 0.0) {
    float metallic = m.metallicRoughnessUnlit.x;
    v.iridescenceF = iridescenceFresnel(1.0, m.sheenColorFilmIor.w, max(nDotV, 1e-4), m.film.x,
                                        mixAsGlm(m.dielectric.xyz, m.colorAmbient.xyz, metallic));
  }
  return v;
}
