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

const float PI = 3.14159265358979;

#ifdef CLASSIC
vec3 shadeAmbient(Surface s) { return s.albedo * s.ambient; }

vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
  float nDotL = max(dot(s.n, l), 0.0);
  vec3 h = normalize(l + s.toEye);
  float spec = nDotL > 0.0 ? s.specular * pow(max(dot(s.n, h), 0.0), s.shininess) : 0.0;
  return radiance * visibility * (s.albedo * s.diffuse * nDotL + vec3(spec));
}
#else
float distributionGgx(float nDotH, float alpha) {
  float a2 = alpha * alpha;
  float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

float visibilitySmith(float nDotL, float nDotV, float alpha) {
  float a2 = alpha * alpha;
  float gl = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
  float gv = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
  return 0.5 / max(gl + gv, 1e-6);
}

vec3 shadeAmbient(Surface s) {
  vec3 sky = mix(u_ambientGround.rgb, u_ambientSky.rgb, 0.5 + 0.5 * s.n.y);
  vec3 diffuseColor = s.albedo * (1.0 - s.metallic);
  vec3 f0 = mix(vec3(0.04), s.albedo, s.metallic);
  return sky * (diffuseColor + f0 * (1.0 - s.roughness) * 0.5);
}

vec3 shadeLight(Surface s, vec3 l, vec3 radiance, float visibility) {
  float nDotL = max(dot(s.n, l), 0.0);
  if (nDotL <= 0.0 || visibility <= 0.0) return vec3(0.0);
  vec3 h = normalize(l + s.toEye);
  float nDotV = max(dot(s.n, s.toEye), 1e-4);
  float nDotH = max(dot(s.n, h), 0.0);
  float vDotH = max(dot(s.toEye, h), 0.0);
  float alpha = max(s.roughness * s.roughness, 1e-3);
  vec3 f0 = mix(vec3(0.04), s.albedo, s.metallic);
  vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
  vec3 specular = fresnel * distributionGgx(nDotH, alpha) * visibilitySmith(nDotL, nDotV, alpha);
  vec3 diffuse = (1.0 - fresnel) * (1.0 - s.metallic) * s.albedo / PI;
  // Lights are given as the radiance a white Lambert surface facing them reflects,
  // so PI cancels the Lambert 1/PI: a sun of colour c makes such a surface c.
  return radiance * visibility * nDotL * PI * (diffuse + specular);
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
