// The two material models. CLASSIC is the course's: colour * (ambient + diffuse *
// N.L * visibility) (+ a Blinn-Phong highlight); mirrors add reflection * the
// environment. PBR is glTF's metallic-roughness with GGX, Smith and Schlick.
struct Surface {
  vec3 albedo;
  vec3 n;
  vec3 toEye;
  vec3 position;
  float metallic;
  float roughness;
  float ambient;
  float diffuse;
  float specular;
  float shininess;
  float reflection;
};

// The BRDFs themselves live in common/brdf.glsl, which the C++ tracers compile too.
#include "common/brdf.glsl"

const float PI = BRDF_PI;

#ifdef CLASSIC
vec3 shadeAmbient(Surface s) { return s.albedo * s.ambient; }

vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
  return radiance * visibility *
         classicReflected(s.n, s.toEye, l, s.albedo, s.diffuse, s.specular, s.shininess);
}
#else
vec3 shadeAmbient(Surface s) {
  vec3 sky = mix(u_ambientGround.rgb, u_ambientSky.rgb, 0.5 + 0.5 * s.n.y);
  vec3 diffuseColor = s.albedo * (1.0 - s.metallic);
  vec3 f0 = metallicF0(s.albedo, s.metallic);
  return sky * (diffuseColor + f0 * (1.0 - s.roughness) * 0.5);
}

vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
  float nDotL = dot(s.n, l);
  if (nDotL <= 0.0 || visibility <= 0.0) return vec3(0.0);
  vec3 f = metallicRoughnessBrdf(s.n, s.toEye, l, s.albedo, s.metallic, s.roughness);
  return radiance * visibility * brdfLightFactor(f, nDotL);
}
#endif

#ifdef REFLECTION_PROBES
// A mirror reflects the cube map of the scene seen from its centre: right in
// direction, off by parallax for things close to the mirror, one bounce only. The
// ray tracer traces the reflected ray itself; the difference is measured.
layout(binding = 8) uniform samplerCube u_reflectionProbe;
uniform int u_hasProbe;

vec3 reflectedEnvironment(Surface s) {
  if (u_hasProbe == 0 || s.reflection <= 0.0) return vec3(0.0);
  return s.reflection * texture(u_reflectionProbe, reflect(-s.toEye, s.n)).rgb;
}
#else
// Without probes a mirror shows only its own shading.
vec3 reflectedEnvironment(Surface s) { return vec3(0.0 * s.reflection); }
#endif
