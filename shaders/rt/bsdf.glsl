// The GPU path tracer's scattering at one hit: common/bsdf.glsl, the text the CPU's
// Bsdf compiles (raytrace/bsdf.h), for a material as rtMaterialAt gives it, with the
// view's terms from rt/view_layers.glsl. After common/sampling.glsl,
// rt/materials.glsl, rt/environment_light.glsl, common/brdf.glsl and
// rt/view_layers.glsl.
#include "common/bsdf.glsl"

// raytrace/bsdf.cpp's scatteringOf, from the material buffer's packing.
BsdfMaterial bsdfMaterialOf(RtMaterial m) {
  BsdfMaterial s;
  s.albedo = m.colorAmbient.xyz;
  s.diffuse = m.diffuseSpecularShininessReflection.x;
  s.specular = m.diffuseSpecularShininessReflection.y;
  s.shininess = m.diffuseSpecularShininessReflection.z;
  s.reflection = m.diffuseSpecularShininessReflection.w;
  s.metallic = m.metallicRoughnessUnlit.x;
  s.roughness = m.metallicRoughnessUnlit.y;
  s.dielectricF0 = m.dielectric.xyz;
  s.dielectricF90 = m.dielectric.w;
  s.clearcoat = m.coatSheen.x;
  s.clearcoatRoughness = m.coatSheen.y;
  s.sheenRoughness = m.coatSheen.z;
  s.iridescence = m.coatSheen.w;
  s.sheenColor = m.sheenColorFilmIor.xyz;
  s.transmission = m.transmission.x;
  s.ior = m.transmission.y;
  s.thickness = m.transmission.z;
  return s;
}

// Bsdf::classic or Bsdf::metallicRoughness: n the unit shading normal on the
// viewer's side, wo toward the viewer, `entering` from outside the surface.
Bsdf bsdfOf(RtMaterial m, bool metallicRoughness, vec3 n, vec3 wo, bool entering) {
  Bsdf b = bsdfAbout(bsdfMaterialOf(m), metallicRoughness, n, wo, entering);
  if (metallicRoughness) b = bsdfViewed(b, n, rtViewLayers(m, n, bsdfCosView(b)));
  return b;
}

// Bsdf::sample: false when it draws nothing.
bool bsdfSample(Bsdf b, vec2 u, float uLobe, out BsdfSample s) {
  s = bsdfSampleOf(b, u, uLobe);
  return s.drawn;
}
