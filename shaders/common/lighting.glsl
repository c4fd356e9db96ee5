// Classic lighting, in linear colour: hemispheric ambient from the sky plus one
// directional sun, Lambert diffuse and Blinn-Phong specular.
struct Sun {
  vec3 direction;  // toward the sun, normalised
  vec3 color;
};

vec3 hemisphereAmbient(vec3 n, vec3 skyColor, vec3 groundColor) {
  return mix(groundColor, skyColor, 0.5 + 0.5 * n.y);
}

vec3 blinnPhong(vec3 albedo, vec3 n, vec3 toEye, Sun sun, float specular, float shininess) {
  float nDotL = max(dot(n, sun.direction), 0.0);
  vec3 h = normalize(sun.direction + toEye);
  // No highlight on the side facing away from the sun.
  float spec = nDotL > 0.0 ? pow(max(dot(n, h), 0.0), shininess) : 0.0;
  return sun.color * (albedo * nDotL + vec3(specular * spec));
}
